#include "uavplan/coordination/contract/arrival_points.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

Scenario shared_goal(std::vector<Vec3> starts, double separation) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 100, 40)};
  Scenario sc;
  sc.world = World(std::move(ws));
  for (std::size_t i = 0; i < starts.size(); ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = starts[i];
    u.goal = Vec3(50, 50, 20);
    sc.uavs.push_back(u);
  }
  sc.mission.separation_m = separation;
  return sc;
}

double least_gap(const std::vector<Arrival>& a) {
  double gap = 1e300;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size(); ++j) gap = std::min(gap, (a[i].point - a[j].point).norm());
  return gap;
}

TEST(ArrivalPoints, AUavAloneEndsAtItsGoal) {
  Scenario sc = shared_goal({Vec3(5, 50, 20), Vec3(95, 50, 20)}, 4);
  sc.uavs[1].goal = Vec3(80, 80, 20);
  const auto a = arrival_points(sc);
  EXPECT_EQ(a[0].point, *sc.uavs[0].goal);
  EXPECT_EQ(a[0].tolerance_m, 0.0);
  EXPECT_TRUE(a[0].problem.empty());
}

TEST(ArrivalPoints, SharedGoalsEndApartOnTheSideEachComesFrom) {
  const Scenario sc = shared_goal({Vec3(5, 50, 20), Vec3(50, 5, 20), Vec3(95, 50, 20)}, 4);
  const auto a = arrival_points(sc);
  EXPECT_GE(least_gap(a), 4.0);
  EXPECT_LT(a[0].point.x(), 50.0);  // from the west
  EXPECT_LT(a[1].point.y(), 50.0);  // from the south
  EXPECT_GT(a[2].point.x(), 50.0);  // from the east
  for (const Arrival& x : a) {
    EXPECT_DOUBLE_EQ(x.tolerance_m, (x.point - Vec3(50, 50, 20)).norm());
    EXPECT_DOUBLE_EQ(x.point.z(), 20.0);
  }
}

TEST(ArrivalPoints, UavsFromOneSideArriveSideBySide) {
  const auto a = arrival_points(shared_goal({Vec3(5, 48, 20), Vec3(5, 52, 20)}, 4));
  EXPECT_GE(least_gap(a), 4.0);
  const Vec3 d = a[1].point - a[0].point;
  EXPECT_GT(std::abs(d.y()), 3.0 * std::abs(d.x()));  // abreast across the approach from the west
}

TEST(ArrivalPoints, GoalSpacingWidensButNeverNarrowsTheSeparation) {
  Scenario sc = shared_goal({Vec3(5, 50, 20), Vec3(95, 50, 20)}, 4);
  sc.mission.goal_spacing_m = 10;
  EXPECT_GE(least_gap(arrival_points(sc)), 10.0);
  sc.mission.goal_spacing_m = 1;
  EXPECT_GE(least_gap(arrival_points(sc)), 4.0);
  sc.uavs[0].clearance_m = 3;  // bodies with clearance: 0.5 + 3 + 0.5
  EXPECT_GE(least_gap(arrival_points(sc)), 4.0);
  sc.uavs[1].clearance_m = 3;
  EXPECT_GE(least_gap(arrival_points(sc)), 7.0);
}

TEST(ArrivalPoints, TheRingTurnsAwayFromObstaclesAndSaysWhenThereIsNoRoom) {
  Scenario sc = shared_goal({Vec3(5, 50, 20), Vec3(95, 50, 20)}, 6);
  WorldSpec ws = sc.world.spec();
  ws.obstacles.push_back(Box{Vec3(40, 40, 0), Vec3(48, 60, 40)});  // the west side of the goal
  sc.world = World(std::move(ws));
  auto a = arrival_points(sc);
  for (const Arrival& x : a) {
    EXPECT_TRUE(x.problem.empty()) << x.problem;
    EXPECT_GE(sc.world.clearance(x.point, 1.0), 0.5);
  }
  ws = sc.world.spec();  // a shaft around the goal: 3 m wide, the UAVs need 6 m
  ws.obstacles = {Box{Vec3(0, 0, 0), Vec3(48.5, 100, 40)}, Box{Vec3(51.5, 0, 0), Vec3(100, 100, 40)},
                  Box{Vec3(48, 0, 0), Vec3(52, 48.5, 40)}, Box{Vec3(48, 51.5, 0), Vec3(52, 100, 40)}};
  sc.world = World(std::move(ws));
  a = arrival_points(sc);
  EXPECT_NE(a[0].problem.find("no free room"), std::string::npos) << a[0].problem;
  EXPECT_NE(a[0].problem.find("u1, u2"), std::string::npos) << a[0].problem;
}

}  // namespace
}  // namespace uavplan
