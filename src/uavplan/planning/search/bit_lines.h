// The blocked cells of a 2-D grid as bit lines read 64 cells at a time (JPS2's block-based
// jumps, Harabor and Grastien 2014): the rows, or the columns (the grid transposed, so that a
// vertical jump reads consecutive bits too). Cells outside the grid read as blocked.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "uavplan/planning/search/bit_grid.h"

namespace uavplan {

class BitLines {
 public:
  BitLines() = default;
  // Layer 0 of `grid` by rows (line j holds cells (i, j)) or by columns (line i holds (i, j)).
  BitLines(const BitGrid& grid, bool columns)
      : lines_(columns ? grid.nx() : grid.ny()), length_(columns ? grid.ny() : grid.nx()) {
    bits_.assign(static_cast<std::size_t>((static_cast<std::int64_t>(lines_) * length_ + 63) / 64 + 1), 0);
    for (int l = 0; l < lines_; ++l)
      for (int p = 0; p < length_; ++p)
        if (columns ? grid.blocked(l, p, 0) : grid.blocked(p, l, 0)) {
          const std::int64_t idx = static_cast<std::int64_t>(l) * length_ + p;
          bits_[static_cast<std::size_t>(idx >> 6)] |= std::uint64_t{1} << (idx & 63);
        }
  }

  int lines() const { return lines_; }
  int length() const { return length_; }
  std::size_t memory_bytes() const { return bits_.capacity() * sizeof(std::uint64_t); }

  // Bit b set when cell `from + b` of `line` is blocked (or outside the grid), b in [0, 64).
  std::uint64_t window(int line, std::int64_t from) const {
    if (line < 0 || line >= lines_) return ~std::uint64_t{0};
    const std::int64_t lo = std::max<std::int64_t>(from, 0), hi = std::min<std::int64_t>(from + 64, length_);
    if (lo >= hi) return ~std::uint64_t{0};
    const std::int64_t idx = static_cast<std::int64_t>(line) * length_ + lo;
    const auto word = static_cast<std::size_t>(idx >> 6);
    const int off = static_cast<int>(idx & 63);
    std::uint64_t v = bits_[word] >> off;
    if (off) v |= bits_[word + 1] << (64 - off);  // the padding word keeps word + 1 in range
    const int n = static_cast<int>(hi - lo);
    if (n < 64) v |= ~std::uint64_t{0} << n;  // past the line's end
    const int shift = static_cast<int>(lo - from);
    if (shift) v = v << shift | ((std::uint64_t{1} << shift) - 1);  // before its start
    return v;
  }

 private:
  int lines_ = 0, length_ = 0;
  std::vector<std::uint64_t> bits_;  // line-major, one zero word of padding
};

}  // namespace uavplan
