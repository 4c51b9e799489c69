#include "uavplan/simulation/trajectory.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

TEST(Trajectory, TimesARouteAtConstantSpeed) {
  const std::vector<Vec3> pts{{0, 0, 0}, {10, 0, 0}, {10, 5, 0}};
  const Trajectory tr = time_route(pts, 2.0, 3.0, 1.0);
  EXPECT_DOUBLE_EQ(tr.front().t_s, 0.0);
  EXPECT_EQ(tr[1].p, pts[0]);
  EXPECT_DOUBLE_EQ(tr[1].t_s, 3.0);  // waits at the start until departure
  EXPECT_DOUBLE_EQ(tr.back().t_s, 3.0 + 7.5);
  for (std::size_t i = 1; i < tr.size(); ++i)
    if (tr[i].p != tr[i - 1].p) {
      EXPECT_LE(tr[i].t_s - tr[i - 1].t_s, 1.0 + 1e-12);
    }
  EXPECT_TRUE((position_at(tr, 9.0) - Vec3(10, 2, 0)).norm() < 1e-12);
  EXPECT_EQ(position_at(tr, -5), pts[0]);
  EXPECT_EQ(position_at(tr, 1e9), pts[2]);
}

TEST(Trajectory, ClosestApproachAgainstSampling) {
  Rng r(6);
  for (int k = 0; k < 50; ++k) {
    std::vector<Vec3> a{{r.uniform(0, 50), r.uniform(0, 50), 5}}, b{{r.uniform(0, 50), r.uniform(0, 50), 5}};
    for (int i = 0; i < 4; ++i) {
      a.emplace_back(r.uniform(0, 50), r.uniform(0, 50), r.uniform(0, 10));
      b.emplace_back(r.uniform(0, 50), r.uniform(0, 50), r.uniform(0, 10));
    }
    const Trajectory ta = time_route(a, r.uniform(1, 5), r.uniform(0, 5), 2.0);
    const Trajectory tb = time_route(b, r.uniform(1, 5), r.uniform(0, 5), 0.7);
    const Encounter e = closest_approach(ta, tb);
    double sampled = 1e300;
    const double t_end = std::max(ta.back().t_s, tb.back().t_s) + 1;
    for (double t = 0; t <= t_end; t += 0.001)
      sampled = std::min(sampled, (position_at(ta, t) - position_at(tb, t)).norm());
    ASSERT_LE(e.distance_m, sampled + 1e-9);
    ASSERT_NEAR(e.distance_m, sampled, 0.02);
    ASSERT_NEAR((position_at(ta, e.t_s) - position_at(tb, e.t_s)).norm(), e.distance_m, 1e-9);
  }
}

TEST(Trajectory, ClosestApproachUpToAHorizonAndOnSharedTimes) {
  Rng r(8);
  for (int k = 0; k < 50; ++k) {
    std::vector<Vec3> a{{r.uniform(0, 20), r.uniform(0, 20), 0}}, b{{r.uniform(0, 20), r.uniform(0, 20), 0}};
    for (int i = 0; i < 3; ++i) {
      a.emplace_back(r.uniform(0, 20), r.uniform(0, 20), 0);
      b.emplace_back(r.uniform(0, 20), r.uniform(0, 20), 0);
    }
    // Equal speeds and sampling: many sample times coincide.
    const Trajectory ta = time_route(a, 2.0, 0.0, 0.5), tb = time_route(b, k % 2 ? 2.0 : 3.0, 0.0, 0.5);
    const double horizon = r.uniform(-1.0, 1.2 * ta.back().t_s);
    const Encounter e = closest_approach(ta, tb, horizon);
    double sampled = 1e300;
    for (double t = std::min(0.0, horizon); t <= horizon; t += 0.001)
      sampled = std::min(sampled, (position_at(ta, t) - position_at(tb, t)).norm());
    sampled = std::min(sampled, (position_at(ta, horizon) - position_at(tb, horizon)).norm());
    ASSERT_LE(e.distance_m, sampled + 1e-9);
    ASSERT_NEAR(e.distance_m, sampled, 0.01);
    ASSERT_LE(e.t_s, std::max(horizon, 0.0) + 1e-12);
  }
  // A single sample each: where they stand.
  const Trajectory one{{0.0, Vec3(0, 0, 0)}}, other{{0.0, Vec3(3, 4, 0)}};
  EXPECT_DOUBLE_EQ(closest_approach(one, other).distance_m, 5.0);
}

// Random routes with departure delays (so the trajectories start and end at different times),
// and their swept boxes.
struct Flights {
  Flights(std::uint64_t seed, int count, double side_m, int slices)
      : trs(random(seed, count, side_m)), ptrs(pointers(trs)), boxes(ptrs, slices) {}
  static std::vector<const Trajectory*> pointers(const std::vector<Trajectory>& trs) {
    std::vector<const Trajectory*> out;
    out.reserve(trs.size());
    for (const auto& t : trs) out.push_back(&t);
    return out;
  }
  static std::vector<Trajectory> random(std::uint64_t seed, int count, double side_m) {
    Rng r(seed);
    std::vector<Trajectory> out;
    out.reserve(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      std::vector<Vec3> pts;
      pts.reserve(4);
      for (int i = 0; i < 4; ++i) pts.emplace_back(r.uniform(0, side_m), r.uniform(0, side_m), r.uniform(0, 20));
      out.push_back(time_route(pts, r.uniform(2, 8), r.uniform(0, 20), 1.0));
    }
    return out;
  }
  std::vector<Trajectory> trs;
  std::vector<const Trajectory*> ptrs;
  SweptBoxes boxes;
};

TEST(Trajectory, SweptBoxesNeverOverstateTheClosestApproach) {
  const Flights f(9, 30, 200, 16);
  int pruned = 0;
  for (std::size_t i = 0; i < f.trs.size(); ++i)
    for (std::size_t j = i + 1; j < f.trs.size(); ++j) {
      const double exact = closest_approach(f.trs[i], f.trs[j]).distance_m;
      ASSERT_LE(f.boxes.lower_bound_m(i, j), exact + 1e-12);
      pruned += f.boxes.lower_bound_m(i, j) > 5.0;
    }
  EXPECT_GT(pruned, 100) << "the bound is useful: most far pairs are cleared";
}

TEST(Trajectory, PairsWithinAreExactlyThePairsWhoseBoundIsBelowTheReach) {
  const Flights f(11, 60, 300, 16);
  const std::uint32_t n = static_cast<std::uint32_t>(f.trs.size());
  for (const double reach : {0.5, 5.0, 20.0, 80.0, f.boxes.extent_m() * 1.01}) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
    for (std::uint32_t i = 0; i < n; ++i)
      for (std::uint32_t j = i + 1; j < n; ++j)
        if (f.boxes.lower_bound_m(i, j) < reach) expected.emplace_back(i, j);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const auto& p : f.boxes.pairs_within(reach)) {
      EXPECT_EQ(p.bound_m, f.boxes.lower_bound_m(p.i, p.j));
      got.emplace_back(p.i, p.j);
    }
    EXPECT_EQ(got, expected) << "reach " << reach;
  }
  EXPECT_EQ(f.boxes.pairs_within(f.boxes.extent_m() * 1.01).size(), n * (n - 1) / 2);
}

TEST(Trajectory, ClosestBelowEqualsTheClosestApproachWhereItIsBelow) {
  const Flights f(12, 40, 150, 32);
  int below = 0;
  for (std::size_t i = 0; i < f.trs.size(); ++i)
    for (std::size_t j = i + 1; j < f.trs.size(); ++j) {
      const Encounter exact = closest_approach(f.trs[i], f.trs[j]);
      // Over the whole span: the same encounter.
      const Encounter whole = closest_approach_between(f.trs[i], f.trs[j], -1.0, 1e6);
      ASSERT_NEAR(whole.distance_m, exact.distance_m, 1e-9);
      for (const double cut : {5.0, 15.0, 40.0}) {
        const Encounter e = f.boxes.closest_below(f.ptrs, i, j, cut);
        if (exact.distance_m < cut) {
          ++below;
          ASSERT_NEAR(e.distance_m, exact.distance_m, 1e-9) << i << " " << j << " below " << cut;
        } else {
          ASSERT_GE(e.distance_m, cut - 1e-9);
        }
      }
    }
  EXPECT_GT(below, 50);
}

TEST(Trajectory, MovingObstacleAfterArrivalCounts) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-100, -100, 0), Vec3(100, 100, 20)};
  ws.moving.push_back({"late", 1.0, Vec3(50, -100, 5), Vec3(0, 1, 0)});  // passes (50, 0) at t = 100
  const World w(std::move(ws));
  const std::vector<Vec3> pts{{0, 0, 5}, {50, 0, 5}};
  const Trajectory tr = time_route(pts, 5.0, 0.0, 1.0);  // arrives at t = 10 and stays
  EXPECT_LT(closest_moving_approach(w, tr).distance_m, 0.0);
}

TEST(Trajectory, PathObstacleStoppingOnTheGoalCountsAfterArrival) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-100, -100, 0), Vec3(100, 100, 20)};
  // Reaches the goal (50, 0) at t = 60, long after the UAV, and stays there.
  ws.moving.push_back({"parks", 1.0, Vec3::Zero(), Vec3::Zero(), {{0, Vec3(50, -90, 5)}, {60, Vec3(50, 0, 5)}}});
  const World w(std::move(ws));
  const std::vector<Vec3> pts{{0, 0, 5}, {50, 0, 5}};
  const Encounter e = closest_moving_approach(w, time_route(pts, 5.0, 0.0, 1.0));
  EXPECT_LT(e.distance_m, 0.0);
}

}  // namespace
}  // namespace uavplan
