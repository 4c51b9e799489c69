// Take-off and landing from the ground, min_agl and clearance through the whole pipeline:
// planned, verified and measured.
#include <gtest/gtest.h>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {
namespace {

// 200 x 200 x 60 m over sloped terrain, a 35 m block across the middle.
World hills_world() {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 200, 60)};
  ws.terrain = TerrainGrid(Vec2(0, 0), 50.0, 4, 4, {0, 2, 4, 6, 0, 3, 6, 9, 1, 4, 8, 12, 0, 2, 4, 6});
  ws.obstacles.push_back(Box{Vec3(90, 60, 0), Vec3(110, 140, 35)});
  return World(std::move(ws));
}

// UAVs standing on the ground (terrain and floor) lift off and land vertically, keep min_agl in
// between, and two sent to one landing spot touch down apart.
TEST(GroundOps, GroundStartsAndGoalsTakeOffAndLandApart) {
  Scenario sc;
  sc.world = hills_world();
  for (int i = 0; i < 2; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = Vec3(20, 60 + 80 * i, sc.world.ground_z(20, 60 + 80 * i));
    u.goal = Vec3(180, 100, sc.world.ground_z(180, 100));
    u.speed = {0, 5, 5};
    u.max_climb_rad = deg_to_rad(30);
    u.min_agl_m = 8;
    u.clearance_m = 1;
    sc.uavs.push_back(u);
  }
  sc.mission.separation_m = 5;
  MissionOptions opt;
  opt.params = {{"cell_m", "4"}};
  Plan p = plan_mission(sc, opt);
  ASSERT_EQ(p.status, Status::solved) << p.message;
  for (std::size_t i = 0; i < 2; ++i) {
    const Trajectory& tr = p.uavs[i].trajectory;
    EXPECT_EQ(tr.front().p, sc.uavs[i].start);
    EXPECT_EQ(tr.front().t_s, 0.0);
    EXPECT_TRUE(sc.world.on_ground(tr.back().p));
    std::size_t k = 1;  // the first rows climb straight up
    while (tr[k].p.head<2>() == tr[0].p.head<2>()) ++k;
    EXPECT_GE(tr[k - 1].p.z() - sc.world.ground_z(20, tr[0].p.y()), 8.0 + 1.5);
  }
  EXPECT_GE((p.uavs[0].trajectory.back().p - p.uavs[1].trajectory.back().p).norm(), 5.0);
  EXPECT_TRUE(verify_plan(sc, p).empty()) << describe(verify_plan(sc, p).front());
  compute_metrics(sc, p);
  EXPECT_LE(p.uavs[0].metrics.at("max_climb_deg"), 30.0 + 1e-6);
  EXPECT_GE(p.uavs[0].metrics.at("min_agl_m"), 8.0 - 1e-6);
}

// A UAV with a home takes off there, flies to its start, on to its goal and back, and lands
// at home: planned, verified and measured (its arrival the first time at its goal); the verifier
// fails a flight that skips its home or its start.
TEST(GroundOps, AHomeIsWhereTheFlightBeginsAndEnds) {
  Scenario sc;
  sc.world = hills_world();
  UavSpec u;
  u.id = "u1";
  u.home = Vec3(20, 20, sc.world.ground_z(20, 20));
  u.start = Vec3(40, 100, 20);
  u.goal = Vec3(170, 100, 25);
  u.speed = {0, 5, 5};
  u.max_climb_rad = deg_to_rad(30);
  sc.uavs.push_back(u);
  MissionOptions opt;
  opt.params = {{"cell_m", "4"}};
  Plan p = plan_mission(sc, opt);
  ASSERT_EQ(p.status, Status::solved) << p.message;
  const Trajectory& tr = p.uavs[0].trajectory;
  EXPECT_EQ(tr.front().p, *u.home);
  EXPECT_LT((tr.back().p - *u.home).norm(), 1e-9);
  EXPECT_TRUE(verify_plan(sc, p).empty()) << describe(verify_plan(sc, p).front());
  compute_metrics(sc, p);
  double at_goal = 1e300;
  for (const TrajectorySample& row : tr)
    if ((row.p - *u.goal).norm() < 1e-6) at_goal = std::min(at_goal, row.t_s);
  EXPECT_NEAR(p.uavs[0].arrival_s, at_goal - kMinArrivalRadius_m / 5.0, 1e-6);  // within 0.5 m at 5 m/s
  EXPECT_LT(p.uavs[0].arrival_s, tr.back().t_s);
  // A flight from the start (the home skipped) and one straight from home to the goal fail.
  Plan skip_home = p;
  std::erase_if(skip_home.uavs[0].trajectory, [&](const TrajectorySample& r) { return r.t_s < at_goal / 4.0; });
  bool start = false;
  for (const Violation& v : verify_plan(sc, skip_home)) start = start || v.kind == ViolationKind::start;
  EXPECT_TRUE(start);
  Plan direct = p;
  direct.uavs[0].trajectory = {{0.0, *u.home}, {40.0, *u.goal}, {80.0, *u.home}};
  start = false;
  for (const Violation& v : verify_plan(sc, direct)) start = start || v.kind == ViolationKind::start;
  EXPECT_TRUE(start);
}

// A start straight above home ends the climb from home, and a goal straight above home begins the
// descent to it: no leg straight up or down is left to a planner with turn and climb limits (P5's
// PSO failed such a leg, and the field planner passed its start off the column). Each planner
// plans, the plan verifies, and the take-off (landing) column reaches the start (leaves the goal).
TEST(GroundOps, AStartOrGoalStraightAboveHomeIsWhereTheClimbEnds) {
  for (const char* algorithm : {"astar", "pso_mpc", "apf"})
    for (const bool start_above : {true, false}) {
      Scenario sc;
      sc.world = hills_world();
      UavSpec u;
      u.id = "u1";
      u.home = Vec3(20, 20, sc.world.ground_z(20, 20));
      u.start = start_above ? Vec3(20, 20, 30) : Vec3(40, 100, 20);
      u.goal = start_above ? Vec3(170, 100, 25) : Vec3(20, 20, 40);
      u.speed = {0, 5, 5};
      u.max_climb_rad = deg_to_rad(30);
      sc.uavs.push_back(u);
      MissionOptions opt;
      opt.algorithm = algorithm;
      opt.params = {{"cell_m", "4"}};
      const Plan p = plan_mission(sc, opt);
      const std::string what = std::string(algorithm) + (start_above ? ", start above home" : ", goal above home");
      ASSERT_EQ(p.status, Status::solved) << what << ": " << p.message;
      const std::vector<Violation> bad = verify_plan(sc, p);
      EXPECT_TRUE(bad.empty()) << what << ": " << describe(bad.front());
      const Trajectory& tr = p.uavs[0].trajectory;
      const auto in_column = [&](const TrajectorySample& r) {
        return (r.p.head<2>() - u.home->head<2>()).norm() < 1e-9;
      };
      const Vec3 end = start_above ? u.start : *u.goal;  // where the column's climb ends or descent begins
      if (start_above) {
        std::size_t k = 0;
        while (k + 1 < tr.size() && in_column(tr[k + 1])) ++k;
        EXPECT_LT((tr[k].p - end).norm(), 1e-9) << what;
      } else {
        std::size_t k = tr.size() - 1;
        while (k > 0 && in_column(tr[k - 1])) --k;
        EXPECT_LT((tr[k].p - end).norm(), 1e-9) << what;
      }
    }
}

}  // namespace
}  // namespace uavplan
