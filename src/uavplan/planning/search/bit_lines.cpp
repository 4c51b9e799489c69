#include "uavplan/planning/search/bit_lines.h"

namespace uavplan {
namespace {

// Bits pos .. pos + 63 of `w` (bits past its end read as 0).
std::uint64_t read64(const std::vector<std::uint64_t>& w, std::int64_t pos) {
  const auto i = static_cast<std::size_t>(pos >> 6);
  const int off = static_cast<int>(pos & 63);
  std::uint64_t v = i < w.size() ? w[i] >> off : 0;
  if (off && i + 1 < w.size()) v |= w[i + 1] << (64 - off);
  return v;
}

// Sets the set bits of `bits` at pos .. pos + 63 (the caller keeps w one word longer).
void or64(std::vector<std::uint64_t>& w, std::int64_t pos, std::uint64_t bits) {
  const auto i = static_cast<std::size_t>(pos >> 6);
  const int off = static_cast<int>(pos & 63);
  w[i] |= bits << off;
  if (off) w[i + 1] |= bits >> (64 - off);
}

// Bit c of a[r] becomes bit r of a[c]: the off-diagonal halves swapped, then their quarters, ...
// (Warren, Hacker's Delight 7-3, for 64 bits with bit 0 first).
void transpose64(std::uint64_t a[64]) {
  std::uint64_t m = 0x00000000FFFFFFFFULL;
  for (int j = 32; j != 0; j >>= 1, m ^= m << j)
    for (int k = 0; k < 64; k = ((k | j) + 1) & ~j) {
      const std::uint64_t t = ((a[k] >> j) ^ a[k | j]) & m;
      a[k] ^= t << j;
      a[k | j] ^= t;
    }
}

}  // namespace

void BitLines::transpose_from(const BitGrid& g, int axis) {
  const int nx = g.nx(), ny = g.ny();
  const int others = axis == 1 ? g.nz() : ny;  // the values of w
  std::uint64_t block[64];
  for (int w = 0; w < others; ++w)
    for (int r0 = 0; r0 < length_; r0 += 64) {
      const int rows = std::min(64, length_ - r0);
      for (int i0 = 0; i0 < nx; i0 += 64) {
        const int cols = std::min(64, nx - i0);
        const std::uint64_t keep = cols == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << cols) - 1;
        bool any = false;
        for (int r = 0; r < 64; ++r) {
          block[r] = 0;
          if (r >= rows) continue;
          const std::int64_t rr = r0 + r;
          const std::int64_t row = axis == 1 ? (static_cast<std::int64_t>(w) * ny + rr) * nx : (rr * ny + w) * nx;
          block[r] = read64(g.words(), row + i0) & keep;
          any = any || block[r] != 0;
        }
        if (!any) continue;
        transpose64(block);
        for (int c = 0; c < cols; ++c)
          if (block[c]) or64(bits_, (static_cast<std::int64_t>(w) * across_ + i0 + c) * length_ + r0, block[c]);
      }
    }
}

}  // namespace uavplan
