// Missions flown in the closed loop (UAVs with sensor_range), checked by the verifier against
// the obstacles' true motion.
#include <gtest/gtest.h>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/coordination/planning_view.h"
#include "uavplan/core/rng.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {
namespace {

// Random worlds like the ones the local layer is judged on: crossing, head-on, overtaking and
// turning obstacles across the UAVs' straight routes, flat or 3-D, sensors of 20-100 m.
Scenario random_world(std::uint64_t seed) {
  Rng r(seed);
  const bool three_d = r.uniform01() < 0.5;
  const double size = r.uniform(150, 400), top = three_d ? r.uniform(40, 100) : 0.0;
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(size, size, top)};
  Scenario sc;
  sc.name = "sensing" + std::to_string(seed);
  sc.mission.separation_m = r.uniform(1, 4);
  const int n = static_cast<int>(r.uniform_int(1, 6));
  const double range = r.uniform(20, 100);
  for (int i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    const double z0 = three_d ? r.uniform(10, top - 10) : 0.0, z1 = three_d ? r.uniform(10, top - 10) : 0.0;
    const double lane = size * (i + 0.5) / n;  // starts and goals well apart
    u.start = i % 2 ? Vec3(10, lane, z0) : Vec3(lane, 10, z0);
    u.goal = i % 2 ? Vec3(size - 10, r.uniform(10, size - 10), z1) : Vec3(r.uniform(10, size - 10), size - 10, z1);
    u.radius_m = r.uniform(0.3, 1.0);
    const double v = r.uniform(3, 10);
    u.speed = {0, v, v};
    u.sensor_range_m = range;
    sc.uavs.push_back(u);
  }
  for (int k = 0; k < static_cast<int>(r.uniform_int(1, 6)); ++k) {
    const UavSpec& u = sc.uavs[static_cast<std::size_t>(r.uniform_int(0, n - 1))];
    const Vec3 d = (*u.goal - u.start).normalized();
    const double f = r.uniform(0.3, 0.7), t_meet = f * (*u.goal - u.start).norm() / u.speed.cruise_mps;
    const Vec3 meet = u.start + f * (*u.goal - u.start), side = Vec3(-d.y(), d.x(), 0).normalized();
    const double v = r.uniform(1, 7), radius = r.uniform(1, 4);
    MovingObstacle m;
    m.id = "m" + std::to_string(k);
    m.radius_m = radius;
    switch (k % 4) {
      case 0:
        m.velocity_mps = v * side;
        break;  // crossing
      case 1:
        m.velocity_mps = -v * d;
        break;  // head-on
      case 2:
        m.velocity_mps = 1.5 * u.speed.cruise_mps * d;
        break;  // overtaking
      default:  // turning
        m.path = {
            {t_meet - 40.0 / v, meet + 40 * side + 10 * d}, {t_meet, meet}, {t_meet + 40.0 / v, meet - 40 * side}};
    }
    if (m.path.empty()) m.position = meet - t_meet * m.velocity_mps;
    bool clear_start = true;
    for (const UavSpec& o : sc.uavs) clear_start &= (m.position_at(0) - o.start).norm() > radius + 5;
    if (clear_start) ws.moving.push_back(m);
  }
  sc.world = World(std::move(ws));
  sc.planner.algorithm = "improved_rrt";
  return sc;
}

TEST(SensingFlight, SolvedPlansHoldAgainstTheTrueMotionAndMostAreSolved) {
  int uavs = 0, solved = 0, replanned = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const Scenario sc = random_world(seed);
    Plan plan = plan_mission(sc, {});
    for (const UavPlan& u : plan.uavs) replanned += u.message.find(" 0 local replans") == std::string::npos;
    const auto violations = finalize_plan(sc, plan);
    for (const UavPlan& u : plan.uavs) {
      ++uavs;
      if (u.status != Status::solved) continue;
      ++solved;
      for (const Violation& v : violations) EXPECT_NE(v.uav, u.id) << "seed " << seed << ": solved but " << describe(v);
    }
  }
  EXPECT_GE(solved, uavs * 9 / 10) << solved << " of " << uavs;
  EXPECT_GT(replanned, 10) << "the obstacles were in the way";
}

TEST(SensingFlight, AnObstacleFasterThanTheUavHeadOnInACorridorFailsItWithTheReason) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(300, 40, 0)};
  ws.obstacles.push_back(Box{Vec3(0, -1, -1), Vec3(300, 17, 1)});  // a corridor 6 m wide
  ws.obstacles.push_back(Box{Vec3(0, 23, -1), Vec3(300, 41, 1)});
  ws.moving.push_back({"bullet", 2.5, Vec3(290, 20, 0), Vec3(-15, 0, 0)});
  Scenario sc;
  sc.world = World(std::move(ws));
  UavSpec u;
  u.id = "u1";
  u.start = Vec3(10, 20, 0);
  u.goal = Vec3(280, 20, 0);
  u.speed = {0, 5, 5};
  u.sensor_range_m = 50;
  sc.uavs.push_back(u);
  sc.planner.algorithm = "improved_rrt";
  Plan plan = plan_mission(sc, {});
  finalize_plan(sc, plan);
  EXPECT_EQ(plan.uavs[0].status, Status::failed);
  EXPECT_EQ(plan.uavs[0].reason, Reason::conflict);  // not no_route: the route was there, the obstacle in it
  EXPECT_NE(plan.uavs[0].message.find("could not avoid moving obstacle 'bullet'"), std::string::npos)
      << plan.uavs[0].message;
}

// A sortie from home (take-off, start, goal, back home) meets an obstacle it senses near its goal:
// the local route rejoins the sortie at its goal, not past it on the way home, whenever the
// obstacle comes (each passes the route 0-13 m beyond the goal, 50-66 s after t = 0).
TEST(SensingFlight, ASortiesDetourRejoinsAtItsGoalNotOnTheWayHome) {
  for (const double meet_s : {50.0, 58.0, 66.0})
    for (const double x : {290.0, 296.0, 303.0}) {
      WorldSpec ws;
      ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(400, 200, 60)};
      MovingObstacle kite;
      kite.id = "kite";
      kite.radius_m = 4;
      kite.path = {{0.0, Vec3(x, 40, 20)}, {meet_s, Vec3(x, 100, 20)}, {2 * meet_s, Vec3(x, 160, 20)}};
      ws.moving.push_back(kite);
      Scenario sc;
      sc.world = World(std::move(ws));
      sc.mission.separation_m = 2;
      UavSpec u;
      u.id = "u";
      u.home = Vec3(20, 100, 0);
      u.start = Vec3(20, 100, 20);
      u.goal = Vec3(300, 100, 20);
      u.speed = {0, 5, 5};
      u.sensor_range_m = 30;
      sc.uavs.push_back(u);
      sc.default_min_agl_m = default_min_agl_m(sc);
      sc.planner.algorithm = "astar";
      Plan plan = plan_mission(sc, {});
      const auto violations = finalize_plan(sc, plan);
      EXPECT_EQ(plan.status, Status::solved) << meet_s << " s, x " << x << ": " << plan.uavs[0].message;
      EXPECT_TRUE(violations.empty()) << meet_s << " s, x " << x << ": " << describe(violations.front());
    }
}

TEST(SensingFlight, UavsWithoutSensorsFlyAsTimedAndTheOthersSeeThem) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 200, 0)};
  Scenario sc;
  sc.world = World(std::move(ws));
  UavSpec blind, seer;
  blind.id = "blind";
  blind.start = Vec3(100, 10, 0);
  blind.goal = Vec3(100, 190, 0);
  blind.speed = {0, 5, 5};
  seer.id = "seer";
  seer.start = Vec3(10, 100, 0);
  seer.goal = Vec3(190, 100, 0);
  seer.speed = {0, 5, 5};
  seer.sensor_range_m = 40;
  sc.uavs = {blind, seer};
  sc.mission.separation_m = 5;
  sc.planner.algorithm = "improved_rrt";
  Plan plan = plan_mission(sc, {});
  const auto violations = finalize_plan(sc, plan);
  EXPECT_TRUE(violations.empty()) << describe(violations.front());
  EXPECT_EQ(plan.status, Status::solved) << plan.message;
  EXPECT_NE(plan.uavs[1].message.find("flown in the loop"), std::string::npos);
  Plan again = plan_mission(sc, {});
  finalize_plan(sc, again);
  for (std::size_t i = 0; i < plan.uavs.size(); ++i) {
    ASSERT_EQ(plan.uavs[i].trajectory.size(), again.uavs[i].trajectory.size());
    for (std::size_t k = 0; k < plan.uavs[i].trajectory.size(); ++k)
      EXPECT_EQ(plan.uavs[i].trajectory[k].p, again.uavs[i].trajectory[k].p);
  }
}

}  // namespace
}  // namespace uavplan
