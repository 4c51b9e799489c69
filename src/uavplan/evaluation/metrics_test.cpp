#include "uavplan/evaluation/metrics.h"
#include "uavplan/coordination/formation/formation_mission.h"

#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/random_worlds.h"

namespace uavplan {
namespace {

TEST(Metrics, P3ScoreOfAStraightAndABentRoute) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20, 20, 0)};
  ws.obstacles.push_back(Sphere{Vec3(5, 8, 0), 1.0});
  const World w(std::move(ws));
  const std::vector<Vec3> straight{{0, 0, 0}, {5, 0, 0}, {10, 0, 0}};
  const P3Score s = p3_score(straight, w);
  EXPECT_DOUBLE_EQ(s.y1, 10.0);
  EXPECT_DOUBLE_EQ(s.s1, 1.0);
  EXPECT_NEAR(s.y3, 0.0, 1e-12);  // theta = pi
  const double y2 = 1.0 / (std::hypot(5.0, 8.0) - 1) + 1.0 / 7.0 + 1.0 / (std::hypot(5.0, 8.0) - 1);
  EXPECT_NEAR(s.y2, y2, 1e-12);
  EXPECT_NEAR(s.s2, y2 / 3, 1e-12);
  const std::vector<Vec3> bent{{0, 0, 0}, {5, 5, 0}, {10, 0, 0}};
  const P3Score b = p3_score(bent, w);
  EXPECT_NEAR(b.y3, 1.0 / (kPi / 2) - 1.0 / kPi, 1e-12);
  EXPECT_GT(b.sc, s.sc);
}

TEST(Metrics, P1CostWeighsThreatAndLength) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(10, 10, 10)};
  ws.radars.push_back({Vec3(3, 1, 0), 1.0});
  const World w(std::move(ws));
  const std::vector<Vec3> pts{{0, 0, 0}, {6, 0, 0}};
  EXPECT_NEAR(p1_route_cost(pts, w), 0.5 * w.p1_threat_cost(pts[0], pts[1]) + 0.5 * 6.0, 1e-12);
}

// One name, one meaning: a UAV's length_m is the distance flown (its metrics' length_m);
// route_length_m, the planned waypoints' polyline, stays as the mission set it.
TEST(Metrics, LengthIsTheFlownLengthBesideTheRoutes) {
  Scenario sc;
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20, 20, 20)};
  sc.world = World(std::move(ws));
  UavSpec u;
  u.id = "u";
  u.start = {0, 0, 10};
  u.goal = Vec3(10, 0, 10);
  sc.uavs = {u};
  Plan plan;
  UavPlan up;
  up.id = "u";
  up.status = Status::solved;
  up.waypoints = {{0, 0, 10}, {10, 0, 10}};
  up.route_length_m = 10.0;
  up.trajectory = {{0.0, Vec3(0, 0, 10)}, {1.0, Vec3(5, 3, 10)}, {2.0, Vec3(10, 0, 10)}};
  plan.uavs = {up};
  compute_metrics(sc, plan);
  EXPECT_DOUBLE_EQ(plan.uavs[0].length_m, 2.0 * std::sqrt(34.0));
  EXPECT_EQ(plan.uavs[0].length_m, plan.uavs[0].metrics.at("length_m"));
  EXPECT_EQ(plan.uavs[0].route_length_m, 10.0);
  plan.uavs[0].trajectory.clear();
  compute_metrics(sc, plan);
  EXPECT_EQ(plan.uavs[0].length_m, 0.0) << "a UAV that flew nothing";
}

// A reversal: the direction of flight turning by more than 120 deg within 3 s, hovers skipped.
TEST(Metrics, ReversalsAreSharpTurnsBackWithinSeconds) {
  const auto track = [](const std::vector<std::pair<double, Vec3>>& rows) {
    Trajectory tr;
    for (const auto& [t, p] : rows) tr.push_back({t, p});
    return tr;
  };
  // East, back west, east again: two reversals; a 90 deg corner is none.
  EXPECT_EQ(count_reversals(track({{0, {0, 0, 0}}, {1, {5, 0, 0}}, {2, {1, 0, 0}}, {3, {6, 0, 0}}})), 2);
  EXPECT_EQ(count_reversals(track({{0, {0, 0, 0}}, {1, {5, 0, 0}}, {2, {5, 5, 0}}})), 0);
  // Back after a 1 s hover still counts; after a 5 s hover it is a new leg, not a reversal.
  EXPECT_EQ(count_reversals(track({{0, {0, 0, 0}}, {1, {5, 0, 0}}, {2, {5, 0, 0}}, {3, {1, 0, 0}}})), 1);
  EXPECT_EQ(count_reversals(track({{0, {0, 0, 0}}, {1, {5, 0, 0}}, {6, {5, 0, 0}}, {7, {1, 0, 0}}})), 0);
}

// Time in shape: from the form-up's end to arrival, less the UAV's breaks; backing up: distance
// flown against the group's mean direction of travel.
TEST(Metrics, TimeInShapeAndBackingUp) {
  FormationLog log;
  log.phases = {{"form_up", 10.0}, {"formation", 100.0}};
  log.breaks = {{"u1", 30.0, 45.0}, {"u2", 95.0, 120.0}};
  EXPECT_DOUBLE_EQ(time_in_shape_s(log, "u1", shape_window(log, 100.0)), 75.0);
  EXPECT_DOUBLE_EQ(time_in_shape_s(log, "u2", shape_window(log, 100.0)), 85.0);  // its break runs past its arrival
  EXPECT_DOUBLE_EQ(time_in_shape_s(log, "u3", shape_window(log, 60.0)), 50.0);
  log.phases = {{"form_up", 10.0}, {"mission", 50.0}, {"return", 80.0}, {"dismiss", 90.0}};
  EXPECT_DOUBLE_EQ(time_in_shape_s(log, "u3", shape_window(log, 200.0)), 70.0);  // P5: up to the dismissal
  // Three fly east; one of them backs up 2 m in the middle second.
  Trajectory a{{0, {0, 0, 0}}, {1, {5, 0, 0}}, {2, {10, 0, 0}}}, b{{0, {0, 5, 0}}, {1, {5, 5, 0}}, {2, {10, 5, 0}}},
      c{{0, {0, -5, 0}}, {1, {-2, -5, 0}}, {2, {10, -5, 0}}};
  const std::vector<const Trajectory*> group{&a, &b, &c};
  EXPECT_DOUBLE_EQ(backing_up_m(a, group, 0.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(backing_up_m(c, group, 0.0, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(backing_up_m(c, group, 1.0, 2.0), 0.0);  // outside the window
}

// P1's wedge around two no-fly cylinders with nothing moving: the wingmen follow the turning
// reference without shuttling (no reversal once formed, though no turn limit is given), do not
// back up, and arrive together, each at its goal to stay.
TEST(Metrics, AWedgeTurningAroundObstaclesNeitherShuttlesNorBacksUp) {
  const std::vector<Vec3> wedge{{0, 0, 0}, {-5, 5, 0}, {-5, -5, 0}};
  const Vec3 centroid(-10.0 / 3.0, 0, 0);
  for (const double dy : {-60.0, -20.0, 25.0, 70.0}) {
    Scenario sc;
    sc.name = "wedge_turns";
    WorldSpec ws;
    ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(400, 300, 0)};
    ws.obstacles.push_back(Cylinder{Vec2(130, 150 + dy), 30.0, -1.0, 1.0});
    ws.obstacles.push_back(Cylinder{Vec2(270, 150 - dy), 30.0, -1.0, 1.0});
    for (int k = 0; k < 6; ++k) ws.radars.push_back({Vec3(60.0 + 55.0 * k, k % 2 ? 40.0 : 260.0, 0.0), 1e5});
    sc.world = World(std::move(ws));
    sc.mission.type = "formation";
    sc.mission.separation_m = 2.0;
    sc.mission.edit_section<FormationSection>().shape = wedge;
    for (std::size_t i = 0; i < 3; ++i) {
      UavSpec u;
      u.id = "u" + std::to_string(i + 1);
      u.start = Vec3(30, 150, 0) + (wedge[i] - centroid);
      u.goal = Vec3(370, 150, 0) + (wedge[i] - centroid);
      u.radius_m = 0.5;
      u.speed = {0, 5, 5};
      sc.uavs.push_back(u);
    }
    MissionOptions opt;
    opt.algorithm = "aco_voronoi";
    Plan plan = plan_mission(sc, opt);
    ASSERT_EQ(plan.status, Status::solved) << "dy " << dy << ": " << plan.uavs[0].message;
    compute_metrics(sc, plan);
    ASSERT_TRUE(plan.formation);
    EXPECT_TRUE(plan.formation->breaks.empty()) << "dy " << dy;
    EXPECT_LE(plan.metrics.at("arrival_spread_s"), formation_section(sc).arrival_tolerance_s) << "dy " << dy;
    const double formed_s = plan.formation->phases.front().end_s;
    for (const UavPlan& u : plan.uavs) {
      Trajectory formed;
      for (const TrajectorySample& row : u.trajectory)
        if (row.t_s >= formed_s) formed.push_back(row);
      EXPECT_EQ(count_reversals(formed), 0) << "dy " << dy << " " << u.id << " shuttles";
      EXPECT_LT(u.metrics.at("backing_up_m"), 0.01 * u.metrics.at("length_m")) << "dy " << dy << " " << u.id;
    }
  }
}

}  // namespace
}  // namespace uavplan
