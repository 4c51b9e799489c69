// A UAV with a model flies its waypoints through P5's autopilot: smooth, within its limits, ending
// on the last waypoint; without one it is the point mass of time_route.
#include "uavplan/simulation/vehicle_flight.h"

#include <gtest/gtest.h>

#include <cmath>

namespace uavplan {
namespace {

UavSpec fixed_wing() {
  UavSpec u;
  u.id = "fw";
  u.speed = {70, 150, 200};
  u.max_turn_rate_rad_s = deg_to_rad(3.0);
  u.max_climb_rate_mps = 20;
  u.model = AutopilotParams{};
  return u;
}

TEST(VehicleFlight, TheModelFliesTheCornerRoundWithinItsLimitsAndEndsOnTheGoal) {
  const UavSpec u = fixed_wing();
  const std::vector<Vec3> route{{0, 0, 5000}, {30000, 0, 5000}, {30000, 30000, 5500}};
  const Trajectory tr = fly_route(u, route, 0.0, 0.0);
  ASSERT_GT(tr.size(), 100u);
  EXPECT_EQ(tr.back().p, route.back());
  double prev_heading = 0.0, widest_miss = 1e300;
  for (std::size_t k = 1; k < tr.size(); ++k) {
    const double dt = tr[k].t_s - tr[k - 1].t_s;
    ASSERT_GT(dt, 0.0);
    const Vec3 d = tr[k].p - tr[k - 1].p;
    EXPECT_LE(d.head<2>().norm() / dt, 200.0 + 1e-6);
    EXPECT_LE(std::abs(d.z()) / dt, 20.0 + 1e-6);
    const double heading = std::atan2(d.y(), d.x());
    if (k > 1 && dt >= 0.99) {  // one-second rows: the heading moves at most 3 deg/s (and rounding)
      EXPECT_LE(std::abs(std::remainder(heading - prev_heading, 2 * kPi)), deg_to_rad(3.0) * dt + 1e-3);
    }
    prev_heading = heading;
    widest_miss = std::min(widest_miss, (tr[k].p - route[1]).norm());
  }
  // The corner is cut on an arc: it passes inside, not through it, within the switch radius.
  EXPECT_GT(widest_miss, 100.0);
  EXPECT_LT(widest_miss, 150.0 / deg_to_rad(3.0));
  // It takes longer than the point mass (it slows into nothing, but the arc and the climb cost time).
  EXPECT_NE(tr.back().t_s, time_route(route, 150, 0.0, 0.0).back().t_s);
}

TEST(VehicleFlight, WithoutAModelItIsThePointMass) {
  UavSpec u = fixed_wing();
  u.model.reset();
  const std::vector<Vec3> route{{0, 0, 0}, {100, 0, 0}, {100, 100, 0}};
  const Trajectory a = fly_route(u, route, 5.0, 1.0), b = time_route(route, 150, 5.0, 1.0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].p, b[k].p);
}

TEST(VehicleFlight, AWaypointTooTightForTheTurnRadiusIsRefused) {
  // 1 km legs zigzagging at 150 m/s with a 5 km turn radius: it would circle the last one.
  UavSpec u = fixed_wing();
  u.max_turn_rate_rad_s = deg_to_rad(1.7);
  const std::vector<Vec3> route{{0, 0, 5000}, {1000, 0, 5000}, {0, 300, 5000}};
  EXPECT_TRUE(fly_route(u, route, 0.0, 0.0).empty());
}

}  // namespace
}  // namespace uavplan
