#include "uavplan/coordination/mission_planner.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

Scenario crossing(double separation) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 200, 50)};
  Scenario sc;
  sc.name = "crossing";
  sc.world = World(std::move(ws));
  for (int i = 0; i < 2; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = i == 0 ? Vec3(10, 100, 20) : Vec3(100, 10, 20);
    u.goal = i == 0 ? Vec3(190, 100, 20) : Vec3(100, 190, 20);
    u.speed = {0, 5, 5};
    sc.uavs.push_back(u);
  }
  sc.mission.separation_m = separation;
  return sc;
}

TEST(MissionPlanner, CrossingUavsKeepTheirSeparationByDepartureDelay) {
  const Scenario sc = crossing(10.0);
  MissionOptions opt;
  const Plan p = plan_mission(sc, opt);
  ASSERT_EQ(p.status, Status::solved) << p.message;
  const Encounter e = closest_approach(p.uavs[0].trajectory, p.uavs[1].trajectory);
  EXPECT_GE(e.distance_m, 10.0);
  // The first UAV departs at once, the second waits.
  EXPECT_NEAR(p.uavs[0].arrival_s, p.uavs[0].route_length_m / 5.0, 1e-9);
  EXPECT_GT(p.uavs[1].arrival_s, p.uavs[1].route_length_m / 5.0);
  // The distance flown, with the planned route's beside it (a straight crossing: the same).
  EXPECT_NEAR(p.uavs[0].length_m, p.uavs[0].route_length_m, 1e-9);
}

TEST(MissionPlanner, MissingGoalFailsThatUavOnly) {
  Scenario sc = crossing(1.0);
  sc.uavs[1].goal.reset();
  const Plan p = plan_mission(sc, {});
  EXPECT_EQ(p.status, Status::partial);
  EXPECT_EQ(p.uavs[1].status, Status::failed);
}

TEST(MissionPlanner, UnknownAlgorithmIsMisuse) {
  MissionOptions opt;
  opt.algorithm = "nope";
  EXPECT_THROW(plan_mission(crossing(1.0), opt), std::invalid_argument);
}

// A gap the body fits through but not with the clearance asked for.
TEST(MissionPlanner, ClearanceNarrowsWhatFits) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 100, 0)};
  ws.obstacles = {Box{Vec3(48, 0, -1), Vec3(52, 48.5, 1)}, Box{Vec3(48, 51.5, -1), Vec3(52, 100, 1)}};
  Scenario sc;
  sc.world = World(std::move(ws));
  UavSpec u;
  u.id = "u1";
  u.start = Vec3(10, 50, 0);
  u.goal = Vec3(90, 50, 0);
  sc.uavs.push_back(u);
  MissionOptions opt;
  opt.params = {{"cell_m", "0.5"}};
  EXPECT_EQ(plan_mission(sc, opt).status, Status::solved);
  sc.uavs[0].clearance_m = 1.2;  // needs 2 x 1.7 m of the 3 m gap
  const Plan p = plan_mission(sc, opt);
  EXPECT_EQ(p.status, Status::failed);
  EXPECT_FALSE(p.uavs[0].message.empty());
}

}  // namespace
}  // namespace uavplan
