#include "uavplan/planning/search/theta_star.h"

#include <gtest/gtest.h>

#include "uavplan/core/geometry.h"
#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// Oracle: the segment between centres touches a blocked cell when its exact distance to that
// cell's closed box is 0.
bool brute_los(const BitGrid& g, const int a[3], const int b[3]) {
  const Vec3 p(a[0] + 0.5, a[1] + 0.5, a[2] + 0.5), q(b[0] + 0.5, b[1] + 0.5, b[2] + 0.5);
  for (int k = std::min(a[2], b[2]) - 1; k <= std::max(a[2], b[2]) + 1; ++k)
    for (int j = std::min(a[1], b[1]) - 1; j <= std::max(a[1], b[1]) + 1; ++j)
      for (int i = std::min(a[0], b[0]) - 1; i <= std::max(a[0], b[0]) + 1; ++i) {
        if (!g.inside(i, j, k) || !g.blocked(i, j, k)) continue;
        const Aabb box{Vec3(i, j, k), Vec3(i + 1, j + 1, k + 1)};
        if (golden_section_min([&](double t) { return box.distance(p + t * (q - p)); }, 0.0, 1.0) < 1e-9) return false;
      }
  return true;
}

TEST(LineOfSight, MatchesTheExactOracle) {
  Rng r(41);
  for (int trial = 0; trial < 40; ++trial) {
    BitGrid g(12, 10, trial % 2 ? 6 : 1);
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < 0.15);
    for (int q = 0; q < 200; ++q) {
      int a[3], b[3];
      for (int k = 0; k < 3; ++k) {
        const int n = k == 0 ? g.nx() : k == 1 ? g.ny() : g.nz();
        a[k] = static_cast<int>(r.uniform_int(0, n - 1));
        b[k] = q % 4 == 0 ? a[k] + static_cast<int>(r.uniform_int(-1, 1)) * (k == 2 ? 0 : 2)
                          : static_cast<int>(r.uniform_int(0, n - 1));
        b[k] = std::clamp(b[k], 0, n - 1);
      }
      if (g.blocked(a[0], a[1], a[2]) || g.blocked(b[0], b[1], b[2])) continue;
      ASSERT_EQ(line_of_sight(g, a, b), brute_los(g, a, b))
          << "(" << a[0] << "," << a[1] << "," << a[2] << ") -> (" << b[0] << "," << b[1] << "," << b[2] << ")";
    }
  }
}

TEST(LazyThetaStar, BetweenTheAnyAngleBoundAndTheGridOptimum) {
  Rng r(43);
  for (int trial = 0; trial < 120; ++trial) {
    const bool flat = trial % 2 == 0;
    BitGrid g(30, 25, flat ? 1 : 10);
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < 0.25);
    GridAStar astar(g, bounding_box_moves(g), GridHeuristic::octile);
    LazyThetaStar theta(g);
    const std::int64_t s = r.uniform_int(0, g.size() - 1), t = r.uniform_int(0, g.size() - 1);
    const GridSearchResult a = astar.search(s, t), th = theta.search(s, t);
    ASSERT_EQ(a.solved(), th.solved());
    if (!a.solved()) continue;
    EXPECT_LE(th.cost, a.cost + 1e-9) << "trial " << trial;
    EXPECT_GE(th.cost, a.cost / (flat ? 1.0824 : 1.128) - 1e-9);
    double len = 0.0;
    for (std::size_t i = 1; i < th.cells.size(); ++i) {
      int p[3], q[3];
      g.coords(th.cells[i - 1], p[0], p[1], p[2]);
      g.coords(th.cells[i], q[0], q[1], q[2]);
      ASSERT_TRUE(line_of_sight(g, p, q));
      len += std::sqrt(
          double((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2])));
    }
    ASSERT_NEAR(len, th.cost, 1e-9);
  }
}

}  // namespace
}  // namespace uavplan
