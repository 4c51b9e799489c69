// P5 eq. 1: each hold answers a step as its time constant says, the limits saturate it, and the
// waypoint follower flies a route through the model within them.
#include "uavplan/vehicle/autopilot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace uavplan {
namespace {

AutopilotLimits fixed_wing() {
  AutopilotLimits l;
  l.speed = {70, 150, 200};
  l.max_turn_rate_rad_s = deg_to_rad(2.2);  // bank 30 deg at 150 m/s (papers.md P5)
  l.max_climb_rate_mps = 20;
  return l;
}

TEST(Autopilot, SpeedAndHeadingHoldsAreFirstOrderWithTheirTimeConstants) {
  AutopilotLimits free;
  free.speed = {0, 150, 300};
  const AutopilotModel m({}, free);
  AutopilotState s;
  s.speed_mps = 100;
  m.advance(s, {150, 0, deg_to_rad(10)}, 5.0);  // tau_v = 5 s; the heading settles in 0.75 s
  EXPECT_NEAR(s.speed_mps, 150 - 50 * std::exp(-1.0), 1e-3);
  EXPECT_NEAR(rad_to_deg(s.heading_rad), 10 * (1 - std::exp(-5.0 / 0.75)), 1e-4);
  AutopilotState h;
  h.speed_mps = 100;
  m.advance(h, {100, 0, deg_to_rad(10)}, 0.75);  // one tau_heading: 63 %
  EXPECT_NEAR(rad_to_deg(h.heading_rad), 10 * (1 - std::exp(-1.0)), 1e-3);
  EXPECT_LE(h.position.norm(), 75.0);  // 75 m flown at 100 m/s along a gentle arc
  EXPECT_GT(h.position.norm(), 74.9);
}

TEST(Autopilot, TurnRateAndClimbRateSaturate) {
  const AutopilotModel m({}, fixed_wing());
  AutopilotState s;
  s.speed_mps = 150;
  m.advance(s, {150, 1000, deg_to_rad(90)}, 10.0);
  EXPECT_NEAR(rad_to_deg(s.heading_rad), 22.0, 1e-6);  // 2.2 deg/s for 10 s
  double prev_z = s.position.z();
  for (int k = 0; k < 100; ++k) {  // climbing 1000 m never faster than 20 m/s
    m.advance(s, {150, 1000, s.heading_rad}, 1.0);
    EXPECT_LE(std::abs(s.climb_rate_mps), 20.0 + 1e-9);
    EXPECT_LE(s.position.z() - prev_z, 20.0 + 1e-9);
    prev_z = s.position.z();
  }
  EXPECT_NEAR(s.position.z(), 1000.0, 1.0);
  // A command below the speed range is flown at its minimum.
  m.advance(s, {10, 1000, s.heading_rad}, 100.0);
  EXPECT_NEAR(s.speed_mps, 70.0, 0.1);
}

TEST(Autopilot, FollowsARouteWithinItsLimits) {
  const AutopilotModel m({}, fixed_wing());
  AutopilotState s;
  s.position = Vec3(0, 0, 5000);
  s.speed_mps = 150;
  s.heading_rad = deg_to_rad(45);
  const std::vector<Vec3> route{{40000, 40000, 5000}, {80000, 40000, 5500}, {80000, 0, 5000}};
  const FollowResult r = follow_waypoints(m, s, route, 150);
  ASSERT_TRUE(r.reached);
  EXPECT_LT(r.closest_to_goal_m, 150 * 0.75 + 1e-6);
  // The turns (45 deg, then 90) begin at their arcs' tangent points, R tan(turn / 2) before the
  // corners (R = 150 / 2.2 deg/s, ~3.9 km), and pass within R (1 / cos(turn / 2) - 1) of them.
  const double radius = 150 / deg_to_rad(2.2);
  EXPECT_NEAR(switch_radius_m(m, 150, deg_to_rad(-45), {}), radius * std::tan(deg_to_rad(22.5)), 1e-6);
  EXPECT_NEAR(switch_radius_m(m, 150, 0.0, {}), 2 * 150 * 0.75, 1e-9);  // straight on: the heading lag
  const double turns[] = {45, 90};
  for (int c = 0; c < 2; ++c) {
    double closest = 1e300;
    for (const FollowSample& f : r.samples) closest = std::min(closest, (f.state.position - route[c]).norm());
    const double half = deg_to_rad(turns[c] / 2);
    EXPECT_LT(closest, radius * (1 / std::cos(half) - 1) + 300.0) << c;
  }
  for (std::size_t k = 1; k < r.samples.size(); ++k) {
    const double dt = r.samples[k].t_s - r.samples[k - 1].t_s;
    const double turn =
        std::abs(std::remainder(r.samples[k].state.heading_rad - r.samples[k - 1].state.heading_rad, 2 * kPi));
    EXPECT_LE(turn, deg_to_rad(2.2) * dt + 1e-9);
    EXPECT_LE(std::abs(r.samples[k].state.position.z() - r.samples[k - 1].state.position.z()), 20.0 * dt + 1e-9);
    EXPECT_GE(r.samples[k].state.speed_mps, 70.0 - 1e-9);
    EXPECT_LE(r.samples[k].state.speed_mps, 200.0 + 1e-9);
  }
  // The same route gives the same flight.
  const FollowResult again = follow_waypoints(m, s, route, 150);
  ASSERT_EQ(again.samples.size(), r.samples.size());
  EXPECT_EQ(again.samples.back().state.position, r.samples.back().state.position);
}

TEST(Autopilot, RefusesTimeConstantsAndLimitsThatAreNotPositive) {
  AutopilotParams p;
  p.tau_z_s = 0.0;
  EXPECT_THROW(AutopilotModel(p, fixed_wing()), std::invalid_argument);
  AutopilotLimits l = fixed_wing();
  l.max_turn_rate_rad_s = -1;
  EXPECT_THROW(AutopilotModel({}, l), std::invalid_argument);
  EXPECT_THROW(AutopilotModel({}, fixed_wing(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace uavplan
