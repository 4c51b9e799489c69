#include "uavplan/evaluation/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace uavplan
