// P5's consensus formation control: the cleaned laws are stable for the default gains, the
// formation converges to its shape in straight flight, and turns 45 -> 15 deg (P5 sec. 4.2(b))
// keeping its spacing above the 50 m safety distance.
#include "uavplan/coordination/formation_mission/consensus.h"

#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/coordination/formation_mission/formation_group.h"

namespace uavplan {
namespace {

const std::vector<Vec3> kDiamond{{0, 0, 0}, {-60, 60, 0}, {-60, -60, 0}, {-120, 0, 0}};

std::vector<AutopilotModel> fixed_wings(std::size_t n) {
  AutopilotLimits lim;
  lim.speed = {70.0, 150.0, 200.0};
  lim.max_turn_rate_rad_s = deg_to_rad(2.2);
  lim.max_climb_rate_mps = 20.0;
  return std::vector<AutopilotModel>(n, AutopilotModel(AutopilotParams{}, lim));
}

double nearest_spacing(const FormationGroup& g) {
  double best = 1e300;
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size(); ++j)
      best = std::min(best, (g.state(i).position - g.state(j).position).norm());
  return best;
}

TEST(Consensus, DefaultGainsAreStableOnCompleteAndRingTopologies) {
  const ConsensusGains g;
  EXPECT_TRUE(gains_stable(complete_topology(4), g));
  const Topology ring{{0, 1, 0, 1}, {1, 0, 1, 0}, {0, 1, 0, 1}, {1, 0, 1, 0}};
  EXPECT_TRUE(gains_stable(ring, g));
  EXPECT_TRUE(topology_connected(ring));
  EXPECT_FALSE(topology_connected({{0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 1, 0}}));
  ConsensusGains printed = g;  // the printed bracket sign: position consensus as positive feedback
  printed.kx_per_s = -g.kx_per_s;
  EXPECT_FALSE(gains_stable(complete_topology(4), printed));
  ConsensusGains undamped = g;
  undamped.k_per_s = 0.0, undamped.kz_s = 0.0;
  EXPECT_FALSE(gains_stable(complete_topology(4), undamped));
}

TEST(Consensus, StraightFlightConvergesToTheShapeAtTheDesiredVelocity) {
  FormationGroup g(fixed_wings(4), kDiamond, complete_topology(4), {}, 0.0);
  const std::vector<Vec3> starts{{0, 0, 5000}, {-300, 200, 5100}, {-100, -400, 4900}, {-500, 50, 5050}};
  for (std::size_t i = 0; i < 4; ++i) {
    AutopilotState s;
    s.position = starts[i];
    s.speed_mps = 140.0 + 5.0 * i;
    s.heading_rad = deg_to_rad(10.0 * i);
    g.launch(i, s, FormationGroup::Launch::in_formation);
  }
  FormationOrder o{150.0, deg_to_rad(30.0), 1.0, std::vector<double>(4, 5000.0)};
  for (int k = 0; k < 3000; ++k) g.step(o, {});
  EXPECT_LT(g.shape_error_m(o), 1.0);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(g.state(i).speed_mps, 150.0, 0.5);
    EXPECT_NEAR(g.state(i).heading_rad, deg_to_rad(30.0), deg_to_rad(0.5));
    EXPECT_NEAR(g.state(i).position.z(), 5000.0, 2.0);
  }
  EXPECT_NEAR(nearest_spacing(g), 60.0 * std::sqrt(2.0), 1.0);
}

// After take-off in turn the UAVs are kilometres apart, on opposite courses: they must meet, not
// chase each other round a turn circle (R = 150 / 2.2 deg/s = 3.9 km) at the turn-rate limit.
TEST(Consensus, UavsKilometresApartOnOppositeCoursesGather) {
  FormationGroup g(fixed_wings(4), kDiamond, complete_topology(4), {}, 0.0);
  const std::vector<Vec3> starts{{0, 0, 5000}, {4000, 3000, 5000}, {-3000, 6000, 5000}, {8000, -2000, 5000}};
  for (std::size_t i = 0; i < 4; ++i) {
    AutopilotState s;
    s.position = starts[i];
    s.speed_mps = 150.0;
    s.heading_rad = deg_to_rad(90.0 * i);
    g.launch(i, s, FormationGroup::Launch::in_formation);
  }
  FormationOrder o{150.0, 0.0, 3.0, std::vector<double>(4, 5000.0)};
  for (int k = 0; k < 6000 && g.shape_error_m(o) > 5.0; ++k) g.step(o, {});
  EXPECT_LT(g.shape_error_m(o), 5.0) << "after " << g.time_s() << " s";
}

// P5 sec. 4.2(b): heading 45 deg, then 15 deg (the largest turn, 30 deg), the diamond of 60 m.
TEST(Consensus, TheFortyFiveToFifteenTurnKeepsTheSafetyDistanceAndPassesTheWaypoint) {
  FormationGroup g(fixed_wings(4), kDiamond, complete_topology(4), {}, 0.0);
  const Vec3 a(0, 0, 5000), b = a + 40000.0 * Vec3(std::cos(deg_to_rad(45.0)), std::sin(deg_to_rad(45.0)), 0.0);
  const Vec3 c = b + 40000.0 * Vec3(std::cos(deg_to_rad(15.0)), std::sin(deg_to_rad(15.0)), 0.0);
  FormationOrder o{150.0, deg_to_rad(45.0), 1.0, std::vector<double>(4, 5000.0)};
  const std::vector<Vec2> off = g.offsets_m(o);
  for (std::size_t i = 0; i < 4; ++i) {
    AutopilotState s;
    s.position =
        Vec3(off[i].x() + 60.0 * std::cos(deg_to_rad(45.0)), off[i].y() + 60.0 * std::sin(deg_to_rad(45.0)), 5000.0);
    s.speed_mps = 150.0;
    s.heading_rad = deg_to_rad(45.0);
    g.launch(i, s, FormationGroup::Launch::in_formation);
  }
  RouteSteering steer({a, b, c}, {}, 150.0 / deg_to_rad(2.2), 300.0);
  double nearest = 1e300, miss = 1e300;
  while (steer.update(g.centroid())) {
    o.heading_rad = steer.heading_rad(g.centroid());
    g.step(o, {});
    nearest = std::min(nearest, nearest_spacing(g));
    miss = std::min(miss, (g.centroid() - b).head<2>().norm());
    ASSERT_LT(g.time_s(), 1000.0);
  }
  EXPECT_GT(nearest, 50.0);                     // P5: minimum 70.5 m, safety distance 50 m
  EXPECT_NEAR(nearest_spacing(g), 84.85, 1.0);  // steady after the turn (P5: about 85 m)
  EXPECT_LT(miss, 1500.0);                      // turned on the arc through the corner
}

}  // namespace
}  // namespace uavplan
