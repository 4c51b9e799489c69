#include "uavplan/evaluation/world_bench.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "uavplan/core/rng.h"
#include "uavplan/core/units.h"
#include "uavplan/world/world.h"

namespace uavplan {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Obstacles of 2-10 m spread so that density stays about the same whatever their number.
World random_world(int n, Rng& rng) {
  const double side = 40.0 * std::sqrt(static_cast<double>(n));
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(side, side, 100)};
  for (int i = 0; i < n; ++i) {
    const Vec3 c(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, 100));
    const double s = rng.uniform(2, 10);
    switch (i % 4) {
      case 0:
        ws.obstacles.push_back(Sphere{c, s});
        break;
      case 1:
        ws.obstacles.push_back(Cylinder{c.head<2>(), s, c.z() - s, c.z() + s});
        break;
      case 2:
        ws.obstacles.push_back(Box{c.array() - s, c.array() + s});
        break;
      default: {
        Prism p;
        const int k = 3 + static_cast<int>(rng.uniform_int(0, 5));
        for (int v = 0; v < k; ++v) {
          const double a = 2 * kPi * v / k, r = s * rng.uniform(0.4, 1.0);  // star-shaped, maybe non-convex
          p.polygon.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
        }
        p.z_min_m = c.z() - s;
        p.z_max_m = c.z() + s;
        ws.obstacles.push_back(std::move(p));
      }
    }
  }
  return World(std::move(ws));
}

}  // namespace

std::vector<WorldBenchRow> run_world_bench(const std::vector<int>& counts, int queries, std::uint64_t seed) {
  std::vector<WorldBenchRow> rows;
  constexpr double kRadius_m = 0.5;
  for (const int n : counts) {
    Rng rng(seed + static_cast<std::uint64_t>(n));
    const World w = random_world(n, rng);
    const double side = w.bounds().max.x();
    std::vector<std::pair<Vec3, Vec3>> segs;
    for (int q = 0; q < queries; ++q) {
      const Vec3 a(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, 100));
      const Vec3 d(rng.normal(), rng.normal(), 0.3 * rng.normal());
      segs.emplace_back(a, a + rng.uniform(5, 50) * d.normalized());
    }
    WorldBenchRow row;
    row.obstacles = n;
    row.queries = queries;
    std::vector<char> fast(segs.size());
    auto t0 = std::chrono::steady_clock::now();
    for (std::size_t q = 0; q < segs.size(); ++q)
      fast[q] = w.segment_collides(segs[q].first, segs[q].second, kRadius_m);
    row.segment_us = 1e6 * seconds_since(t0) / queries;
    t0 = std::chrono::steady_clock::now();
    for (std::size_t q = 0; q < segs.size(); ++q) {
      bool hit = false;
      for (const auto& o : w.obstacles())
        if (segment_distance(o, segs[q].first, segs[q].second) < kRadius_m) {
          hit = true;
          break;
        }
      row.collisions += hit;
      row.mismatches += hit != static_cast<bool>(fast[q]);
    }
    row.segment_brute_us = 1e6 * seconds_since(t0) / queries;
    t0 = std::chrono::steady_clock::now();
    double sink = 0.0;
    for (const auto& s : segs) sink += w.clearance(s.first, 100.0);
    row.point_us = 1e6 * seconds_since(t0) / queries + 0.0 * sink;
    rows.push_back(row);
  }
  return rows;
}

std::string format_world_bench(const std::vector<WorldBenchRow>& rows) {
  std::string out;
  out += strf("%10s %8s %12s %14s %9s %12s %11s %10s\n", "obstacles", "queries", "segment_us", "brute_force_us",
              "speedup", "clearance_us", "collisions", "mismatch");
  for (const auto& r : rows)
    out += strf("%10d %8d %12.2f %14.2f %8.1fx %12.2f %11d %10d\n", r.obstacles, r.queries, r.segment_us,
                r.segment_brute_us, r.segment_brute_us / std::max(r.segment_us, kTinyDivisor), r.point_us, r.collisions,
                r.mismatches);
  return out;
}

}  // namespace uavplan
