#include "uavplan/planning/search/bit_grid.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

TEST(BitGrid, FreeMaskMatchesCellByCellLookups) {
  Rng r(21);
  for (const auto& dims : {std::array<int, 3>{70, 5, 4}, std::array<int, 3>{64, 3, 1}, std::array<int, 3>{1, 1, 1},
                           std::array<int, 3>{129, 7, 3}}) {
    BitGrid g(dims[0], dims[1], dims[2]);
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < 0.4);
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
          std::uint32_t expect = 0;
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di)
                if (g.free(i + di, j + dj, k + dk)) expect |= 1u << ((dk + 1) * 9 + (dj + 1) * 3 + (di + 1));
          ASSERT_EQ(g.free_mask(i, j, k), expect) << i << "," << j << "," << k;
        }
  }
}

TEST(BitGrid, OneBitPerCell) {
  const BitGrid g(896, 390, 255);  // a Warframe A1-sized map
  EXPECT_LE(g.memory_bytes(), static_cast<std::size_t>(g.size() / 8 + 8));
}

}  // namespace
}  // namespace uavplan
