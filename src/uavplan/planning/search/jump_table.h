// Jump Point Search's jumps on a 2-D grid, read from bit lines (JPS2's block-based jumps) or
// from a table computed once per map (JPS+; Harabor and Grastien 2014, "Improving Jump Point
// Search"). No corner cutting: a diagonal step needs both orthogonal neighbours free.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/planning/search/bit_grid.h"
#include "uavplan/planning/search/bit_lines.h"

namespace uavplan {

// Where a straight jump from position p of `line` along `step` (+1 or -1) stops: the first cell
// that is blocked (jump_point false, `at` that cell), is the goal (its position on this line, or
// -1 for none), or has a forced neighbour (a cell of a side line free where the one before it is
// blocked). 63 cells per step of the scan.
struct LineStop {
  std::int64_t at;
  bool jump_point;
};
LineStop scan_line(const BitLines& lines, int line, std::int64_t p, int step, std::int64_t goal);

// For every free cell and each of the 8 directions, the steps to the jump point that a jump
// without a goal reaches (> 0), or minus the free steps before it runs into a dead end (<= 0).
// A diagonal jump stops at the first cell from which a straight jump along either of its
// components reaches a jump point. Steps are 16-bit (16 bytes a cell): half the table of 32-bit
// ones is half the cache misses of a search that reads it all over the map (3-5 % off the
// median query on MovingAI's 512 x 512 maps), and no jump on a grid up to kMaxSide cells a side
// is longer.
class JumpTable {
 public:
  static constexpr int kMaxSide = 32767;
  // Throws std::invalid_argument when the grid is more than kMaxSide cells wide or high.
  JumpTable(const BitGrid& grid, const BitLines& rows, const BitLines& cols);
  static bool fits(const BitGrid& grid) { return grid.nx() <= kMaxSide && grid.ny() <= kMaxSide; }

  // 0..3: +x, -x, +y, -y; 4..7: diagonals (+x+y, -x+y, +x-y, -x-y).
  static int direction(int dx, int dy) {
    if (dy == 0) return dx > 0 ? 0 : 1;
    if (dx == 0) return dy > 0 ? 2 : 3;
    return 4 + (dx < 0 ? 1 : 0) + (dy < 0 ? 2 : 0);
  }
  std::int32_t steps(std::int64_t cell, int direction) const {
    return steps_[static_cast<std::size_t>(cell) * 8 + static_cast<std::size_t>(direction)];
  }
  std::size_t memory_bytes() const { return steps_.capacity() * sizeof(steps_[0]); }

 private:
  std::vector<std::int16_t> steps_;
};

}  // namespace uavplan
