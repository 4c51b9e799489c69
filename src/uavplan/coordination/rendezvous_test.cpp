#include "uavplan/coordination/rendezvous.h"

#include <gtest/gtest.h>

#include "uavplan/coordination/mission_planner.h"

namespace uavplan {
namespace {

Scenario small_rendezvous() {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(30000, 30000, 12000)};
  ws.obstacles.push_back(Sphere{Vec3(12000, 12000, 5000), 3000});
  ws.obstacles.push_back(Sphere{Vec3(20000, 9000, 6000), 2500});
  Scenario sc;
  sc.name = "rv";
  sc.world = World(std::move(ws));
  const Vec3 goal(18000, 18000, 8000);
  const Vec3 starts[3] = {Vec3(2000, 2000, 4000), Vec3(28000, 3000, 4000), Vec3(27000, 27000, 5000)};
  const double headings[3] = {kPi / 2, kPi / 2, kPi};
  for (int i = 0; i < 3; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = starts[i];
    u.goal = goal;
    u.heading_rad = headings[i];
    u.radius_m = 1.0;
    u.speed = {0, 100, 100};
    u.max_turn_rad = deg_to_rad(60);
    u.max_climb_rad = deg_to_rad(30);
    sc.uavs.push_back(u);
  }
  sc.mission.type = MissionType::rendezvous;
  sc.mission.arrival_tolerance_m = 1000;
  sc.planner.algorithm = "directional_astar";
  sc.planner.params = {{"cell_m", "1000"}, {"directions", "6"}};
  return sc;
}

TEST(Rendezvous, LengthsEndWithinEpsilonAndEachStepIsReported) {
  const Scenario sc = small_rendezvous();
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params(sc.planner.params));
  const RendezvousResult r = plan_rendezvous(sc, planner, {});
  double lo = 1e300, hi = 0;
  for (const auto& u : r.uavs) {
    ASSERT_TRUE(u.ok) << u.id << ": " << u.detail;
    EXPECT_NE(u.step, RendezvousStep::none);
    EXPECT_LE(u.final_m, r.target_m + 1e-6);
    EXPECT_GE(u.final_m, r.target_m - r.epsilon_m - 1e-6);
    EXPECT_TRUE(check_route_limits(u.waypoints, sc.uavs[&u - r.uavs.data()]).empty()) << u.id;
    lo = std::min(lo, u.final_m);
    hi = std::max(hi, u.final_m);
  }
  EXPECT_LE(hi - lo, 1000.0);
}

TEST(Rendezvous, ThroughTheMissionPlannerArrivalTimesMatch) {
  const Scenario sc = small_rendezvous();
  const Plan p = plan_mission(sc, {});
  ASSERT_EQ(p.status, Status::solved) << p.message;
  double t_lo = 1e300, t_hi = 0;
  for (const auto& u : p.uavs) {
    t_lo = std::min(t_lo, u.arrival_s);
    t_hi = std::max(t_hi, u.arrival_s);
  }
  EXPECT_LE(t_hi - t_lo, 1000.0 / 100.0 + 1e-6);  // equal speeds: spread <= epsilon / speed
}

TEST(Rendezvous, ImpossibleToleranceFailsClearly) {
  Scenario sc = small_rendezvous();
  sc.mission.arrival_tolerance_m = 1e-3;
  const Plan p = plan_mission(sc, {});
  EXPECT_NE(p.status, Status::solved);
  bool reason = false;
  for (const auto& u : p.uavs) reason |= u.status == Status::failed && u.message.find("no step") != std::string::npos;
  EXPECT_TRUE(reason);
}

}  // namespace
}  // namespace uavplan
