// The blocked cells of a grid as bit lines read 64 cells at a time (JPS2's block-based jumps,
// Harabor and Grastien 2014): the lines along one axis, the grid transposed when that axis is
// not x, so that a jump along any axis reads consecutive bits. Cells outside the grid read as
// blocked.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "uavplan/planning/search/bit_grid.h"

namespace uavplan {

class BitLines {
 public:
  BitLines() = default;
  // The lines of `grid` along `axis` (0 x, 1 y, 2 z): line u + n_u * w holds the cells whose
  // other two coordinates, in x, y, z order, are u and w (a 2-D grid's rows along x, its
  // columns along y).
  BitLines(const BitGrid& grid, int axis) : length_(axis == 0 ? grid.nx() : axis == 1 ? grid.ny() : grid.nz()) {
    const int n[3] = {grid.nx(), grid.ny(), grid.nz()};
    across_ = axis == 0 ? n[1] : n[0];
    lines_ = static_cast<int>(grid.size() / std::max(length_, 1));
    bits_.assign(static_cast<std::size_t>((static_cast<std::int64_t>(lines_) * length_ + 63) / 64 + 1), 0);
    if (axis == 0) {  // the lines along x are the grid's own bits, in its order
      std::copy(grid.words().begin(), grid.words().end(), bits_.begin());
      return;
    }
    transpose_from(grid, axis);
  }

  // The line of the cells with other coordinates (u, w), or -1 when they are outside the grid
  // (a line that reads as blocked).
  int line(int u, int w) const {
    const int along_w = across_ > 0 ? lines_ / across_ : 0;
    return u < 0 || w < 0 || u >= across_ || w >= along_w ? -1 : w * across_ + u;
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
  // Lines along y or z from the grid's rows along x, 64 x 64 cells at a time (a bit-matrix
  // transpose): a building costs the grid's words, however many cells are blocked.
  void transpose_from(const BitGrid& grid, int axis);

  int lines_ = 0, length_ = 0, across_ = 0;  // across_: how many values u takes
  std::vector<std::uint64_t> bits_;          // line-major, one zero word of padding
};

}  // namespace uavplan
