// Compact occupancy store: one bit per cell (set = blocked), x fastest. Cells outside the grid
// count as blocked.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace uavplan {

class BitGrid {
 public:
  BitGrid() = default;
  BitGrid(int nx, int ny, int nz) : n_{nx, ny, nz}, bits_(static_cast<std::size_t>((size() + 63) / 64), 0) {}

  int nx() const { return n_[0]; }
  int ny() const { return n_[1]; }
  int nz() const { return n_[2]; }
  std::int64_t size() const { return static_cast<std::int64_t>(n_[0]) * n_[1] * n_[2]; }
  std::size_t memory_bytes() const { return bits_.capacity() * sizeof(std::uint64_t); }

  std::int64_t index(int i, int j, int k) const { return (static_cast<std::int64_t>(k) * n_[1] + j) * n_[0] + i; }
  void coords(std::int64_t idx, int& i, int& j, int& k) const {
    i = static_cast<int>(idx % n_[0]);
    const std::int64_t r = idx / n_[0];
    j = static_cast<int>(r % n_[1]);
    k = static_cast<int>(r / n_[1]);
  }
  bool inside(int i, int j, int k) const { return i >= 0 && j >= 0 && k >= 0 && i < n_[0] && j < n_[1] && k < n_[2]; }
  bool blocked(std::int64_t idx) const { return (bits_[idx >> 6] >> (idx & 63)) & 1u; }
  bool blocked(int i, int j, int k) const { return !inside(i, j, k) || blocked(index(i, j, k)); }
  bool free(int i, int j, int k) const { return !blocked(i, j, k); }
  // A cell index inside the grid whose cell is free (a search's start or goal).
  bool free(std::int64_t idx) const { return idx >= 0 && idx < size() && !blocked(idx); }
  void set_blocked(std::int64_t idx, bool b = true) {
    const std::uint64_t bit = std::uint64_t{1} << (idx & 63);
    bits_[idx >> 6] = b ? (bits_[idx >> 6] | bit) : (bits_[idx >> 6] & ~bit);
  }

  // Blocks the `count` cells from idx on (consecutive indices), a word at a time.
  void set_blocked_run(std::int64_t idx, std::int64_t count) {
    while (count > 0) {
      const int off = static_cast<int>(idx & 63);
      const int n = static_cast<int>(std::min<std::int64_t>(64 - off, count));
      const std::uint64_t bits = n == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << n) - 1) << off;
      bits_[static_cast<std::size_t>(idx >> 6)] |= bits;
      idx += n;
      count -= n;
    }
  }

  // The bits, 64 cells a word in index order (bits past the last cell are 0).
  const std::vector<std::uint64_t>& words() const { return bits_; }

  // Bit (dk+1)*9 + (dj+1)*3 + (di+1) is set when cell (i+di, j+dj, k+dk) is free, for
  // di, dj, dk in {-1, 0, 1}: one read of three consecutive bits per row instead of 27 lookups.
  std::uint32_t free_mask(int i, int j, int k) const {
    std::uint32_t mask = 0;
    for (int dk = -1; dk <= 1; ++dk) {
      const int kk = k + dk;
      if (kk < 0 || kk >= n_[2]) continue;
      for (int dj = -1; dj <= 1; ++dj) {
        const int jj = j + dj;
        if (jj < 0 || jj >= n_[1]) continue;
        const std::uint32_t row = row_free3(i, jj, kk);
        mask |= row << ((dk + 1) * 9 + (dj + 1) * 3);
      }
    }
    return mask;
  }

 private:
  // Free bits of cells i-1, i, i+1 of a row (bit 0 = i-1).
  std::uint32_t row_free3(int i, int j, int k) const {
    const std::int64_t base = index(0, j, k);
    std::uint32_t occ = 0;
    const std::int64_t first = base + i - 1;
    if (i >= 1 && i + 1 < n_[0]) {
      const std::uint64_t w = bits_[first >> 6] >> (first & 63);
      const int have = 64 - static_cast<int>(first & 63);
      occ = static_cast<std::uint32_t>(w & 7u);
      if (have < 3) occ |= static_cast<std::uint32_t>((bits_[(first >> 6) + 1] << have) & 7u);
    } else {
      for (int d = 0; d < 3; ++d) {
        const int ii = i - 1 + d;
        if (ii < 0 || ii >= n_[0] || blocked(base + ii)) occ |= 1u << d;
      }
    }
    return ~occ & 7u;
  }

  int n_[3] = {0, 0, 0};
  std::vector<std::uint64_t> bits_;
};

}  // namespace uavplan
