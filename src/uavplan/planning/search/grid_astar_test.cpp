#include "uavplan/planning/search/grid_astar.h"

#include <gtest/gtest.h>

#include <queue>

#include "uavplan/core/rng.h"
#include "uavplan/core/vec.h"

namespace uavplan {
namespace {

// Oracle: Dijkstra with the same move rules, written independently and plainly.
double dijkstra(const BitGrid& g, std::int64_t s, std::int64_t t, const Vec3& c, double max_pitch) {
  std::vector<double> dist(g.size(), 1e300);
  using E = std::pair<double, std::int64_t>;
  std::priority_queue<E, std::vector<E>, std::greater<>> pq;
  dist[s] = 0;
  pq.push({0, s});
  while (!pq.empty()) {
    auto [d, u] = pq.top();
    pq.pop();
    if (d > dist[u]) continue;
    if (u == t) return d;
    int i, j, k;
    g.coords(u, i, j, k);
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (!di && !dj && !dk) continue;
          if (!g.inside(i + di, j + dj, k + dk)) continue;
          const Vec3 m(di * c.x(), dj * c.y(), dk * c.z());
          if (dk && std::atan2(std::abs(m.z()), m.head<2>().norm()) > max_pitch) continue;
          bool ok = true;
          for (int a = 0; a <= 1; ++a)
            for (int b = 0; b <= 1; ++b)
              for (int e = 0; e <= 1; ++e)
                if ((a || b || e) && g.blocked(i + a * di, j + b * dj, k + e * dk)) ok = false;
          if (!ok) continue;
          const auto v = g.index(i + di, j + dj, k + dk);
          if (d + m.norm() < dist[v]) {
            dist[v] = d + m.norm();
            pq.push({dist[v], v});
          }
        }
  }
  return -1;
}

TEST(GridAStar, OptimalAgainstDijkstraOnRandomGrids) {
  Rng r(8);
  for (int trial = 0; trial < 60; ++trial) {
    const bool flat = trial % 3 == 0, cubic = trial % 4 < 2;
    BitGrid g(20, 16, flat ? 1 : 8);
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < 0.3);
    const std::int64_t s = r.uniform_int(0, g.size() - 1), t = r.uniform_int(0, g.size() - 1);
    if (g.blocked(s) || g.blocked(t)) continue;
    const Vec3 cell = cubic ? Vec3(1, 1, 1) : Vec3(1, 1, 0.6);
    const double pitch = trial % 2 ? kPi / 2 : deg_to_rad(35);
    GridAStar search(g, bounding_box_moves(g, cell.x(), cell.y(), cell.z(), pitch),
                     cubic && pitch > 1 ? GridHeuristic::octile : GridHeuristic::euclidean, cell.x(), cell.y(),
                     cell.z());
    for (int repeat = 0; repeat < 2; ++repeat) {  // the second query reuses the buffers
      const GridSearchResult p = search.search(s, t);
      const double ref = dijkstra(g, s, t, cell, pitch);
      ASSERT_EQ(p.solved(), ref >= 0) << "trial " << trial;
      if (!p.solved()) continue;
      ASSERT_NEAR(p.cost, ref, 1e-9) << "trial " << trial;
      double len = 0;
      for (std::size_t i = 1; i < p.cells.size(); ++i) {
        int a, b, c, x, y, z;
        g.coords(p.cells[i - 1], a, b, c);
        g.coords(p.cells[i], x, y, z);
        ASSERT_LE(std::max({std::abs(x - a), std::abs(y - b), std::abs(z - c)}), 1);
        len += Vec3((x - a) * cell.x(), (y - b) * cell.y(), (z - c) * cell.z()).norm();
      }
      ASSERT_NEAR(len, p.cost, 1e-9);
      for (const auto c : p.cells) ASSERT_FALSE(g.blocked(c));
    }
  }
}

TEST(GridAStar, HonoursTheStopCondition) {
  BitGrid g(100, 100, 50);
  GridAStar search(g, bounding_box_moves(g), GridHeuristic::euclidean);
  // Euclidean under-estimates the 3-D grid distance, so the search must expand many cells.
  const GridSearchResult p = search.search(0, g.size() - 1, StopCondition::iterations(4096));
  EXPECT_EQ(p.reason, Reason::stopped);
  EXPECT_FALSE(p.solved());
}

TEST(GridAStar, OctileDistance) {
  EXPECT_DOUBLE_EQ(octile_distance(3, 0, 0), 3.0);
  EXPECT_DOUBLE_EQ(octile_distance(2, -2, 0), 2 * std::sqrt(2.0));
  EXPECT_NEAR(octile_distance(1, 2, 3), std::sqrt(3.0) + std::sqrt(2.0) + 1.0, 1e-12);
}

}  // namespace
}  // namespace uavplan
