// Jump Point Search on a 2-D BitGrid (nz == 1) with 8 neighbours and no corner cutting (a
// diagonal move needs both orthogonal neighbours free: MovingAI's rule). Optimal; tested
// against GridAStar. Straight jumps stop where a perpendicular neighbour opens up behind a wall
// (its forced neighbour), found 63 cells at a time on the grid's bit rows and bit columns
// (JPS2's block-based jumps), or read from a table computed once (JPS+, precompute()); diagonal
// jumps stop where a straight jump from them finds anything.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/planning/search/bit_grid.h"
#include "uavplan/planning/search/bit_lines.h"
#include "uavplan/planning/search/grid_astar.h"
#include "uavplan/planning/search/jump_table.h"

namespace uavplan {

class Jps2d {
 public:
  // Throws std::invalid_argument unless grid.nz() == 1. The grid must outlive the object.
  explicit Jps2d(const BitGrid& grid);

  // Computes every cell's jumps once (JPS+): later searches read them instead of scanning. The
  // same jump points, so the same results; costs 16 bytes per cell. A grid more than
  // JumpTable::kMaxSide cells wide or high gets none (false) and is searched by scanning.
  bool precompute();
  bool precomputed() const { return table_.has_value(); }
  std::size_t table_bytes() const { return table_ ? table_->memory_bytes() : 0; }

  // result.cells are the jump points; expand_path() gives every cell.
  GridSearchResult search(std::int64_t start, std::int64_t goal, const StopCondition& stop = {});
  std::vector<std::int64_t> expand_path(const std::vector<std::int64_t>& jump_points) const;

 private:
  struct Expansion;  // jps2d.cpp
  bool free(int x, int y) const { return !grid_->blocked(x, y, 0); }
  bool jump_straight(int& x, int& y, int dx, int dy) const;
  bool jump_diagonal_table(int& x, int& y, int dx, int dy) const;
  template <class Offer>
  void walk_diagonal(int x, int y, int dx, int dy, const Offer& offer) const;
  // The pruned directions from (x, y) reached from `parent`: all eight at the start, else the
  // natural and the forced ones. Returns how many.
  int directions(int x, int y, std::uint32_t parent, int dirs[8][2]) const;

  const BitGrid* grid_;
  BitLines rows_, cols_;  // the grid's blocked cells by rows and by columns, for block jumps
  std::optional<JumpTable> table_;
  int gx_ = 0, gy_ = 0;
  BestFirst<> search_;
};

}  // namespace uavplan
