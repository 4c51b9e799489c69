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
  EXPECT_NEAR(p.uavs[0].arrival_s, p.uavs[0].length_m / 5.0, 1e-9);
  EXPECT_GT(p.uavs[1].arrival_s, p.uavs[1].length_m / 5.0);
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

}  // namespace
}  // namespace uavplan
