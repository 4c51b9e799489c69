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

// Routes are planned on the run's threads at once; each has its own seed, so the plan is the
// one planned one by one, whatever the thread count (rrt: a seeded, sampling planner); a memory
// cap shared among the workers does not change what fits (a route that fails within its share
// is planned again with the whole cap).
TEST(MissionPlanner, RoutesOnManyThreadsAreTheRoutesPlannedOneByOne) {
  Scenario sc = crossing(10.0);
  for (int i = 2; i < 6; ++i) {
    UavSpec u = sc.uavs[i % 2];
    u.id = "u" + std::to_string(i + 1);
    u.start.y() += 5.0 * i;
    u.goal->x() -= 5.0 * i;
    sc.uavs.push_back(u);
  }
  for (const char* algorithm : {"rrt", "astar", "apf"})
    for (int threads : {2, 4}) {
      sc.planner.algorithm = algorithm;
      MissionOptions one;
      one.stop = one.stop.with_threads(1);
      const Plan a = plan_mission(sc, one);
      MissionOptions many;
      many.stop = many.stop.with_threads(threads).with_memory_cap(std::uint64_t{1} << 34);
      const Plan b = plan_mission(sc, many);
      ASSERT_EQ(a.uavs.size(), b.uavs.size());
      for (std::size_t i = 0; i < a.uavs.size(); ++i) {
        EXPECT_EQ(a.uavs[i].status, b.uavs[i].status);
        EXPECT_EQ(a.uavs[i].waypoints, b.uavs[i].waypoints) << i;
        ASSERT_EQ(a.uavs[i].trajectory.size(), b.uavs[i].trajectory.size());
        for (std::size_t k = 0; k < a.uavs[i].trajectory.size(); ++k)
          EXPECT_EQ(a.uavs[i].trajectory[k].t_s, b.uavs[i].trajectory[k].t_s);
      }
    }
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
