#include "uavplan/coordination/rendezvous/rendezvous.h"
#include "uavplan/coordination/rendezvous/rendezvous_mission.h"

#include <gtest/gtest.h>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/core/rng.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {
namespace {

// A UAV of P4's kind: 1 m radius, turns within 60 deg, climbs within 30 deg.
UavSpec p4_uav(int index, const Vec3& start, const Vec3& goal, double heading_rad, double speed_mps) {
  UavSpec u;
  u.id = "u" + std::to_string(index);
  u.start = start;
  u.goal = goal;
  u.heading_rad = heading_rad;
  u.radius_m = 1.0;
  u.speed = {0, speed_mps, speed_mps};
  u.max_turn_rad = deg_to_rad(60);
  u.max_climb_rad = deg_to_rad(30);
  return u;
}

// A rendezvous of `uavs` in `ws` with directional A*'s `params`.
Scenario rendezvous(WorldSpec ws, std::vector<UavSpec> uavs, double tolerance_m, Params params) {
  Scenario sc;
  sc.name = "rv";
  sc.world = World(std::move(ws));
  sc.uavs = std::move(uavs);
  sc.mission.type = "rendezvous";
  sc.mission.edit_section<RendezvousSection>().arrival_tolerance_m = tolerance_m;
  sc.planner.algorithm = "directional_astar";
  sc.planner.params = std::move(params);
  return sc;
}

// UAV i's route: its length inside the window, the limits kept, every segment clear.
void expect_route_holds(const Scenario& sc, const RendezvousResult& r, std::size_t i) {
  const RendezvousUav& u = r.uavs[i];
  EXPECT_GE(u.final_m, r.target_m - r.epsilon_m - 1e-6);
  EXPECT_LE(u.final_m, r.target_m + 1e-6);
  EXPECT_TRUE(check_route_limits(u.waypoints, sc.uavs[i]).empty());
  const SegmentRule rule(sc.world, sc.uavs[i]);
  for (std::size_t k = 1; k < u.waypoints.size(); ++k) EXPECT_TRUE(rule(u.waypoints[k - 1], u.waypoints[k])) << k;
}

Scenario small_rendezvous() {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(30000, 30000, 12000)};
  ws.obstacles.push_back(Sphere{Vec3(12000, 12000, 5000), 3000});
  ws.obstacles.push_back(Sphere{Vec3(20000, 9000, 6000), 2500});
  const Vec3 goal(18000, 18000, 8000);
  return rendezvous(
      std::move(ws),
      {p4_uav(1, Vec3(2000, 2000, 4000), goal, kPi / 2, 100), p4_uav(2, Vec3(28000, 3000, 4000), goal, kPi / 2, 100),
       p4_uav(3, Vec3(27000, 27000, 5000), goal, kPi, 100)},
      1000, {{"cell_m", "1000"}, {"directions", "6"}});
}

TEST(Rendezvous, LengthsEndWithinEpsilonAndEachStepIsReported) {
  const Scenario sc = small_rendezvous();
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params(sc.planner.params));
  const RendezvousResult r = plan_rendezvous(sc, planner, {});
  double lo = 1e300, hi = 0;
  for (const auto& u : r.uavs) {
    ASSERT_TRUE(u.solved()) << u.id << ": " << u.detail;
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

// In a corridor 1.5 km wide and high, a UAV 9 km from the goal cannot fly the 19 km more its
// partner needs: no circle of R_min fits, no detour, no virtual threat leaves a way through.
TEST(Rendezvous, NoRoomToLengthenFailsClearly) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(30000, 1500, 1500)};
  const Vec3 goal(29000, 750, 750);
  const Scenario sc =
      rendezvous(std::move(ws),
                 {p4_uav(1, Vec3(1000, 750, 750), goal, 0.0, 100), p4_uav(2, Vec3(20000, 750, 750), goal, 0.0, 100)},
                 500, {{"cell_m", "250"}, {"min_turn_radius_m", "1000"}});
  const Plan p = plan_mission(sc, {});
  EXPECT_NE(p.status, Status::solved);
  ASSERT_EQ(p.uavs.size(), 2u);
  EXPECT_EQ(p.uavs[0].status, Status::solved) << p.uavs[0].message;
  EXPECT_EQ(p.uavs[1].status, Status::failed);
  EXPECT_NE(p.uavs[1].message.find("no step"), std::string::npos) << p.uavs[1].message;
}

// A flat world of boxes where P4's one state per lattice point leaves the first UAV no route
// (points closed while facing a wall): its pre-plan is searched again with heading sectors.
TEST(Rendezvous, PrePlansFallBackToHeadingSectors) {
  Rng r(8);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20000, 20000, 0)};
  // One draw per statement (the order of a call's arguments differs between compilers), in the
  // order this scene was first drawn in: y before x.
  for (int k = 0; k < 40; ++k) {
    const double y = r.uniform(2000, 18000);
    const double x = r.uniform(2000, 18000);
    ws.obstacles.push_back(Box{Vec3(x, y, -1), Vec3(0, 0, 1)});
  }
  for (auto& o : ws.obstacles) {
    Box& b = std::get<Box>(o);
    const double dy = r.uniform(500, 3000);
    const double dx = r.uniform(500, 3000);
    b.max = b.min + Vec3(dx, dy, 2);
  }
  const Vec3 goal(19000, 19000, 0);
  UavSpec u1 = p4_uav(1, Vec3(1000, 1000, 0), goal, 0.0, 100);
  u1.max_turn_rad = deg_to_rad(r.uniform(30, 60));
  u1.heading_rad = r.uniform(-kPi, kPi);
  UavSpec u2 = u1;
  u2.id = "u2";
  u2.start = Vec3(19000, 1500, 0);
  u2.heading_rad = kPi / 2;
  const Scenario sc = rendezvous(std::move(ws), {u1, u2}, 1000, {{"cell_m", "500"}});
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params(sc.planner.params));
  DirectionalQuery q = planner.query_for(Problem{sc.uavs[0], *sc.uavs[0].goal, {}}, sc.world);
  q.heading_states = false;
  ASSERT_FALSE(DirectionalSearch().run(sc.world, q, {}).solved());  // P4's search alone: none
  const RendezvousResult res = plan_rendezvous(sc, planner, {});
  EXPECT_GT(res.uavs[0].preplanned_m, 0.0) << res.uavs[0].detail;
  EXPECT_TRUE(check_route_limits(res.uavs[0].waypoints, sc.uavs[0]).empty());
}

// A UAV next to the goal needs a loiter of about 10 km, but starts 500 m from the north edge
// heading east: the paper's circle (on the left) leaves the world, no virtual threat fits
// between its start and goal; the loiter on the right does.
TEST(Rendezvous, LoiterGoesWhereItFitsWhenThePapersCircleDoesNot) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20000, 20000, 3000)};
  const Vec3 goal(10000, 17000, 1500);
  const Scenario sc =
      rendezvous(std::move(ws),
                 {p4_uav(1, Vec3(1000, 1000, 1500), goal, 0.0, 50), p4_uav(2, Vec3(7000, 19500, 1500), goal, 0.0, 50)},
                 500, {{"cell_m", "500"}, {"min_turn_radius_m", "500"}});
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params(sc.planner.params));
  const RendezvousResult r = plan_rendezvous(sc, planner, {});
  ASSERT_TRUE(r.uavs[0].solved() && r.uavs[1].solved()) << r.uavs[1].detail;
  const RendezvousUav& near = r.uavs[1];
  EXPECT_EQ(near.step, RendezvousStep::loiter);
  EXPECT_NE(near.detail.find("on the right"), std::string::npos) << near.detail;
  expect_route_holds(sc, r, 1);
}

// 1.2 km short with R_min 1 km: too short for a loiter; a 10 m window that the lattice's
// routes miss. A detour waypoint beside the route makes the length exact.
TEST(Rendezvous, DetourWaypointMakesUpALengthTooShortToLoiter) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20000, 20000, 3000)};
  const Vec3 goal(15000, 15000, 1500);
  const Scenario sc = rendezvous(
      std::move(ws),
      {p4_uav(1, Vec3(1000, 1000, 1500), goal, 0.0, 100), p4_uav(2, Vec3(2500, 1500, 1500), goal, kPi / 2, 100)}, 10,
      {{"cell_m", "500"}, {"min_turn_radius_m", "1000"}});
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params(sc.planner.params));
  const RendezvousResult r = plan_rendezvous(sc, planner, {});
  ASSERT_TRUE(r.uavs[0].solved() && r.uavs[1].solved()) << r.uavs[1].detail;
  const RendezvousUav& u2 = r.uavs[1];
  EXPECT_EQ(u2.step, RendezvousStep::detour) << u2.detail;
  EXPECT_LT(r.target_m - u2.preplanned_m, 2 * kPi * 1000.0);
  EXPECT_DOUBLE_EQ(r.epsilon_m, 10.0);
  expect_route_holds(sc, r, 1);
}

// Two UAVs placed as mirror images about the line to the goal: equal lengths, and their routes
// share lattice points on the way, at the same time. One departs later, within its arrival
// slack, and the separation holds up to their meeting at the goal.
TEST(Rendezvous, ConvergingUavsAreStaggeredWithinTheirSlack) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(30000, 30000, 12000)};
  const Vec3 goal(15000, 15000, 6000);
  Scenario sc = rendezvous(
      std::move(ws),
      {p4_uav(1, Vec3(3000, 14000, 6000), goal, 0.0, 100), p4_uav(2, Vec3(3000, 16000, 6000), goal, 0.0, 100)}, 1000,
      {{"cell_m", "1000"}, {"directions", "6"}});
  sc.mission.separation_m = 200;
  const Plan p = plan_mission(sc, {});
  ASSERT_EQ(p.status, Status::solved) << p.message;
  bool delayed = false;
  for (const auto& u : p.uavs) delayed |= u.message.find("departs") != std::string::npos;
  EXPECT_TRUE(delayed);
  const auto& a = p.uavs[0].trajectory;
  const auto& b = p.uavs[1].trajectory;
  const Encounter e = closest_approach(a, b);  // at the goal too: they end at distinct points
  EXPECT_GE(e.distance_m, 200.0 - 1e-6);
  EXPECT_LE(std::abs(p.uavs[0].arrival_s - p.uavs[1].arrival_s), 1000.0 / 100.0 + 1e-6);
}

}  // namespace
}  // namespace uavplan
