#include "uavplan/planning/search/voxel_astar.h"

#include <gtest/gtest.h>

#include <queue>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// Oracle: Dijkstra with the same move rules, written independently and plainly.
double dijkstra(const VoxelGrid& g, std::int64_t s, std::int64_t t, double max_pitch) {
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
          const Vec3 m(di * g.cell().x(), dj * g.cell().y(), dk * g.cell().z());
          if (dk && std::atan2(std::abs(m.z()), m.head<2>().norm()) > max_pitch) continue;
          bool ok = true;
          for (int a = 0; a <= 1; ++a)
            for (int b = 0; b <= 1; ++b)
              for (int c = 0; c <= 1; ++c)
                if ((a || b || c) && g.blocked(i + a * di, j + b * dj, k + c * dk)) ok = false;
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

TEST(VoxelAStar, OptimalAgainstDijkstraOnRandomGrids) {
  Rng r(8);
  for (int trial = 0; trial < 30; ++trial) {
    VoxelGrid g(Aabb{Vec3(0, 0, 0), Vec3(20, 16, trial % 3 ? 8 : 0)}, Vec3(1, 1, 0.6));
    for (std::int64_t c = 0; c < g.size(); ++c)
      if (r.uniform01() < 0.3) g.set_blocked(c);
    std::int64_t s = r.uniform_int(0, g.size() - 1), t = r.uniform_int(0, g.size() - 1);
    if (g.blocked(s) || g.blocked(t)) continue;
    const double pitch = trial % 2 ? kPi / 2 : deg_to_rad(30);
    VoxelSearchOptions o;
    o.max_pitch_rad = pitch;
    const VoxelPath p = voxel_astar(g, s, t, o, {});
    const double ref = dijkstra(g, s, t, pitch);
    ASSERT_EQ(p.found, ref >= 0) << "trial " << trial;
    if (!p.found) continue;
    ASSERT_NEAR(p.cost_m, ref, 1e-9) << "trial " << trial;
    double len = 0;
    for (std::size_t i = 1; i < p.cells.size(); ++i) len += (g.center(p.cells[i]) - g.center(p.cells[i - 1])).norm();
    ASSERT_NEAR(len, p.cost_m, 1e-9);
    for (const auto c : p.cells) ASSERT_FALSE(g.blocked(c));
  }
}

TEST(VoxelAStar, HonoursTheStopCondition) {
  VoxelGrid g(Aabb{Vec3(0, 0, 0), Vec3(100, 100, 50)}, Vec3(1, 1, 1));
  const VoxelPath p = voxel_astar(g, 0, g.size() - 1, {}, StopCondition::iterations(2000));
  EXPECT_TRUE(p.stopped);
  EXPECT_FALSE(p.found);
}

}  // namespace
}  // namespace uavplan
