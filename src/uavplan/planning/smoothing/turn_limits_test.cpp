#include "uavplan/planning/smoothing/turn_limits.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"
#include "uavplan/planning/segment_rule.h"
#include "uavplan/planning/smoothing/shortcut.h"

namespace uavplan {
namespace {

TEST(TurnLimits, RandomPolylinesComeOutWithinTheLimits) {
  Rng r(12);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-1000, -1000, -1000), Vec3(1000, 1000, 1000)};
  const World w(std::move(ws));
  for (int trial = 0; trial < 200; ++trial) {
    UavSpec u;
    u.radius_m = 0.5;
    u.max_turn_rad = deg_to_rad(r.uniform(20, 90));
    u.max_climb_rad = deg_to_rad(r.uniform(15, 60));
    if (trial % 2) u.heading_rad = r.uniform(-kPi, kPi);
    std::vector<Vec3> pts{Vec3::Zero()};
    for (int k = 0; k < 6; ++k) {
      const double yaw = r.uniform(-kPi, kPi), pitch = r.uniform(-0.8, 0.8) * u.max_climb_rad;
      pts.push_back(pts.back() + r.uniform(20, 100) * Vec3(std::cos(pitch) * std::cos(yaw),
                                                           std::cos(pitch) * std::sin(yaw), std::sin(pitch)));
    }
    std::vector<char> pinned(pts.size(), 0);
    pinned.front() = pinned.back() = 1;
    pinned[3] = 1;  // a via point the route must touch
    const SegmentRule rule(w, u);
    const TurnShaping s = enforce_turn_limits(pts, pinned, u.heading_rad, {u.max_turn_rad, u.max_climb_rad}, rule);
    ASSERT_TRUE(s.solved()) << s.message << " trial " << trial;
    EXPECT_TRUE(check_route_limits(s.waypoints, u).empty()) << "trial " << trial;
    EXPECT_EQ(s.waypoints.front(), pts.front());
    EXPECT_EQ(s.waypoints.back(), pts.back());
    EXPECT_NE(std::find(s.waypoints.begin(), s.waypoints.end(), pts[3]), s.waypoints.end());
  }
}

TEST(TurnLimits, ReversedStartHeadingTurnsAroundWithinTheLimit) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-500, -500, 0), Vec3(500, 500, 100)};
  const World w(std::move(ws));
  UavSpec u;
  u.max_turn_rad = deg_to_rad(30);
  u.heading_rad = kPi;  // facing away from the goal
  const std::vector<Vec3> pts{{0, 0, 50}, {200, 0, 50}};
  const std::vector<char> pinned{1, 1};
  const TurnShaping s =
      enforce_turn_limits(pts, pinned, u.heading_rad, {u.max_turn_rad, u.max_climb_rad}, SegmentRule(w, u));
  ASSERT_TRUE(s.solved()) << s.message;
  EXPECT_TRUE(check_route_limits(s.waypoints, u).empty());
  EXPECT_GT(s.waypoints.size(), 6u);
}

// Out to a via point at the end of a corridor 30 m wide and back (a sortie's goal before the way
// home): a turn toward the far end of the way back swings into the corridor's walls; the route
// turns around beyond the corridor on a tighter turn, rejoins the leg and flies it.
TEST(TurnLimits, AReversalAtAViaPointRejoinsTheLegInsideACorridor) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-100, -500, 0), Vec3(1000, 500, 100)};
  ws.obstacles.push_back(Box{Vec3(200, 15, 0), Vec3(480, 300, 100)});
  ws.obstacles.push_back(Box{Vec3(200, -300, 0), Vec3(480, -15, 100)});
  const World w(std::move(ws));
  UavSpec u;
  u.max_turn_rad = deg_to_rad(60);
  const std::vector<Vec3> pts{{0, 0, 50}, {500, 0, 50}, {0, 0, 50}};
  const std::vector<char> pinned{1, 1, 1};
  const SegmentRule rule(w, u);
  const TurnShaping s = enforce_turn_limits(pts, pinned, std::nullopt, {u.max_turn_rad, u.max_climb_rad}, rule);
  ASSERT_TRUE(s.solved()) << s.message;
  EXPECT_TRUE(check_route_limits(s.waypoints, u).empty());
  EXPECT_NE(std::find(s.waypoints.begin(), s.waypoints.end(), pts[1]), s.waypoints.end());
  EXPECT_EQ(s.waypoints.back(), pts.back());
  for (std::size_t i = 1; i < s.waypoints.size(); ++i) EXPECT_TRUE(rule(s.waypoints[i - 1], s.waypoints[i])) << i;
}

TEST(Shortcut, RemovesRedundantPointsButKeepsPins) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 100, 10)};
  ws.obstacles.push_back(Box{Vec3(40, 0, 0), Vec3(60, 50, 10)});
  const World w(std::move(ws));
  UavSpec u;
  const SegmentRule rule(w, u);
  std::vector<Vec3> pts;
  for (int x = 10; x <= 90; x += 5) pts.emplace_back(x, 55 + (x > 30 && x < 70 ? 5 : 0), 5);
  std::vector<char> pinned(pts.size(), 0);
  pinned.front() = pinned.back() = 1;
  pinned[8] = 1;
  const auto out = shortcut(pts, pinned, rule);
  EXPECT_LT(out.size(), pts.size());
  EXPECT_NE(std::find(out.begin(), out.end(), pts[8]), out.end());
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_TRUE(rule(out[i - 1], out[i]));
}

}  // namespace
}  // namespace uavplan
