#include "uavplan/planning/sampling/rrt.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"
#include "uavplan/planning/sampling/rrt_tree.h"

namespace uavplan {
namespace {

TEST(RrtTree, NearestMatchesBruteForce) {
  Rng r(3);
  RrtTree tree(Vec3::Zero(), 3000);
  std::vector<Vec3> pts{Vec3::Zero()};
  for (int i = 1; i < 3000; ++i) {
    pts.emplace_back(r.uniform(-50, 50), r.uniform(-50, 50), r.uniform(0, 20));
    tree.add(pts.back(), static_cast<int>(r.uniform_int(0, i - 1)));
  }
  for (int q = 0; q < 500; ++q) {
    const Vec3 p(r.uniform(-60, 60), r.uniform(-60, 60), r.uniform(-5, 25));
    double best = World::kInf;
    for (const Vec3& x : pts) best = std::min(best, (x - p).norm());
    EXPECT_DOUBLE_EQ((tree.pos(tree.nearest(p)) - p).norm(), best);
  }
  EXPECT_DOUBLE_EQ(tree.along(5), tree.along(tree.parent(5)) + (tree.pos(5) - tree.pos(tree.parent(5))).norm());
}

TEST(KeepOut, DistanceIsExactInTime) {
  Rng r(8);
  for (int k = 0; k < 200; ++k) {
    const MovingKeepOut ko{Vec3(r.uniform(-10, 10), r.uniform(-10, 10), 0), Vec3(r.uniform(-5, 5), r.uniform(-5, 5), 0),
                           2.0, r.uniform(0, 3)};
    const Vec3 a(r.uniform(-20, 20), r.uniform(-20, 20), 0), b(r.uniform(-20, 20), r.uniform(-20, 20), 0);
    const double ta = r.uniform(0, 5), tb = ta + r.uniform(0.1, 6);
    double sampled = World::kInf;
    for (int i = 0; i <= 20000; ++i) {
      const double f = i / 20000.0;
      sampled = std::min(sampled, (a + f * (b - a) - ko.center_at(ta + f * (tb - ta))).norm());
    }
    const double exact = keep_out_distance(ko, a, ta, b, tb);
    EXPECT_LE(exact, sampled + 1e-9);
    EXPECT_GE(exact, sampled - 0.01);
  }
}

// P1's Table 1 setting: a 40 m x 45 m flat window, the UAV from the bottom to the top, discs of
// moving obstacles across the straight line.
struct Window {
  World world;
  std::vector<MovingKeepOut> discs;
  RrtQuery query;
  UavSpec uav;
};

Window window(std::uint64_t seed, bool moving) {
  Rng r(seed);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(40, 45, 0)};
  Window w{World(std::move(ws)), {}, {}, {}};
  for (int k = 0; k < 3; ++k) {
    const Vec3 v = moving ? Vec3(r.uniform(-3, 3), r.uniform(-1, 1), 0) : Vec3::Zero();
    w.discs.push_back({Vec3(r.uniform(10, 30), 12.0 + 10.0 * k, 0), v, 2.0 + 0.5 + 1.0 * v.norm(), 0.0});
  }
  w.uav.radius_m = 0.5;
  w.uav.speed = {0, 5, 5};
  w.query.start = Vec3(20, 1, 0);
  w.query.goal = Vec3(20, 44, 0);
  w.query.sample_box = w.world.bounds();
  w.query.planar = true;
  w.query.speed_mps = 5;
  w.query.seed = seed;
  return w;  // the caller points query.keep_outs at its discs
}

// Every segment clear of the world and of every keep-out at the times it is flown (sampled).
void expect_route_holds(const Window& w, const std::vector<Vec3>& path, double max_turn) {
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path.front(), w.query.start);
  EXPECT_EQ(path.back(), w.query.goal);
  const SegmentRule rule(w.world, w.uav);
  double along = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    EXPECT_TRUE(rule(path[i - 1], path[i]));
    const double len = (path[i] - path[i - 1]).norm();
    for (int s = 0; s <= 50; ++s) {
      const Vec3 p = path[i - 1] + s / 50.0 * (path[i] - path[i - 1]);
      const double t = (along + s / 50.0 * len) / w.query.speed_mps;
      for (const MovingKeepOut& k : w.discs) EXPECT_GE((p - k.center_at(t)).norm(), k.radius_m - 1e-9);
    }
    if (i >= 2) {
      EXPECT_LE(turn_rad(path[i - 1] - path[i - 2], path[i] - path[i - 1]), max_turn + 1e-6);
    }
    along += len;
  }
}

TEST(Rrt, BothRrtsRouteAroundMovingDiscsAndImprovedIsShorter) {
  double common_m = 0, improved_m = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    Window w = window(seed, true);
    w.query.keep_outs = w.discs;
    const SegmentRule rule(w.world, w.uav);
    const RrtResult c = rrt_search(rule, kPi, w.query, RrtOptions::common(), {});
    const RrtResult i = rrt_search(rule, kPi, w.query, RrtOptions::improved(), {});
    ASSERT_TRUE(c.solved()) << c.message;
    ASSERT_TRUE(i.solved()) << i.message;
    expect_route_holds(w, c.path, kPi);
    expect_route_holds(w, i.path, kPi);
    common_m += Route{c.path}.length_m();
    improved_m += Route{i.path}.length_m();
    EXPECT_LT(i.path.size(), i.raw.size()) << "pruning and the shortcut drop waypoints";
  }
  // P1 Table 1: the improved RRT's local routes are cheaper (8 % here, 200 seeds: 44.3 m vs 47.7 m).
  EXPECT_LT(improved_m, 0.97 * common_m);
}

TEST(Rrt, TurnLimitHoldsAtStartAlongAndIntoTheWayOn) {
  Window w = window(4, false);
  w.query.keep_outs = w.discs;
  w.query.start_direction = Vec3(1, 0, 0);  // flying east at the start
  w.query.goal_direction = Vec3(-1, 0, 0);  // and going on west after the goal
  const double limit = deg_to_rad(45);
  for (const RrtOptions& o : {RrtOptions::common(), RrtOptions::improved()}) {
    const RrtResult r = rrt_search(SegmentRule(w.world, w.uav), limit, w.query, o, {});
    ASSERT_TRUE(r.solved()) << r.message;
    expect_route_holds(w, r.path, limit);
    EXPECT_LE(turn_rad(*w.query.start_direction, r.path[1] - r.path[0]), limit + 1e-6);
    EXPECT_LE(turn_rad(r.path.back() - r.path[r.path.size() - 2], *w.query.goal_direction), limit + 1e-6);
  }
}

TEST(Rrt, ClimbLimitAndThreeDimensions) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(60, 60, 40)};
  ws.obstacles.push_back(Box{Vec3(25, 0, 0), Vec3(35, 60, 20)});  // a wall to climb over
  const World world(std::move(ws));
  UavSpec u;
  u.max_climb_rad = deg_to_rad(20);
  RrtQuery q;
  q.start = Vec3(5, 30, 5);
  q.goal = Vec3(55, 30, 5);
  q.sample_box = world.bounds();
  q.seed = 2;
  const RrtResult r = rrt_search(SegmentRule(world, u), kPi, q, RrtOptions::improved(), {});
  ASSERT_TRUE(r.solved()) << r.message;
  for (std::size_t i = 1; i < r.path.size(); ++i) {
    EXPECT_LE(std::abs(pitch_rad(r.path[i] - r.path[i - 1])), u.max_climb_rad + 1e-7);
    EXPECT_FALSE(world.segment_collides(r.path[i - 1], r.path[i], u.radius_m));
  }
}

TEST(Rrt, BoxedInStartFailsFastAndAStopIsHonoured) {
  Window w = window(1, false);
  w.discs = {{Vec3(20, 1, 0), Vec3::Zero(), 0.5, 0.0}};  // the start is inside: every edge starts in it
  w.query.keep_outs = w.discs;
  w.query.start = Vec3(20, 1.2, 0);
  const RrtResult r = rrt_search(SegmentRule(w.world, w.uav), kPi, w.query, RrtOptions::improved(), {});
  EXPECT_FALSE(r.solved());
  EXPECT_EQ(r.reason, Reason::budget);
  EXPECT_EQ(r.nodes, 1);
  EXPECT_LE(r.iterations, 2000u);
  std::atomic<bool> cancel{true};
  Window m = window(2, true);
  m.query.keep_outs = m.discs;
  const RrtResult s = rrt_search(SegmentRule(m.world, m.uav), kPi, m.query, RrtOptions::improved(),
                                 StopCondition::cancel_flag(&cancel));
  EXPECT_FALSE(s.solved());
  EXPECT_EQ(s.reason, Reason::stopped);
  EXPECT_NE(s.message.find("stopped"), std::string::npos);
}

TEST(Rrt, SameSeedSameRouteAndDifferentSeedsDiffer) {
  Window w = window(9, true);
  w.query.keep_outs = w.discs;
  const SegmentRule rule(w.world, w.uav);
  const RrtResult a = rrt_search(rule, kPi, w.query, RrtOptions::improved(), {});
  const RrtResult b = rrt_search(rule, kPi, w.query, RrtOptions::improved(), {});
  EXPECT_EQ(a.path, b.path);
  RrtQuery other = w.query;
  other.seed = 99;
  EXPECT_NE(rrt_search(rule, kPi, other, RrtOptions::common(), {}).raw, a.raw);
}

TEST(Rrt, StepFollowsTheWorldsScale) {
  RrtOptions o;
  EXPECT_DOUBLE_EQ(o.step_in(Aabb{Vec3::Zero(), Vec3(40, 45, 0)}), 2.0);  // P1's window: the paper's 2 m
  EXPECT_NEAR(o.step_in(Aabb{Vec3::Zero(), Vec3(600, 600, 0)}), std::sqrt(2.0) * 600 / 50, 1e-9);
  o.step_m = 3.5;
  EXPECT_DOUBLE_EQ(o.step_in(Aabb{Vec3::Zero(), Vec3(600, 600, 0)}), 3.5);
  EXPECT_THROW(RrtOptions::from_params({{"lambda", "x"}}, RrtVariant::improved), std::invalid_argument);
  EXPECT_THROW(RrtOptions::from_params({{"lambda", "1"}}, RrtVariant::common),
               std::invalid_argument);  // improved's only
  EXPECT_EQ(RrtOptions::from_params({{"chaotic", "false"}}, RrtVariant::improved).chaotic, false);
}

}  // namespace
}  // namespace uavplan
