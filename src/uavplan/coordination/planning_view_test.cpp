#include "uavplan/coordination/planning_view.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

// One UAV from the ground at (10, 10) to (190, 190) at `goal_z` (0: on the ground).
Scenario from_the_ground(double top_z, double goal_z) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 200, top_z)};
  Scenario sc;
  sc.world = World(std::move(ws));
  UavSpec u;
  u.id = "u1";
  u.start = Vec3(10, 10, 0);
  u.goal = Vec3(190, 190, goal_z);
  sc.uavs.push_back(u);
  return sc;
}

TEST(DefaultMinAgl, AFlightFromTheGroundKeepsPx4sTakeOffHeight) {
  const Scenario sc = from_the_ground(50, 0);
  EXPECT_DOUBLE_EQ(default_min_agl_m(sc), kDefaultMinAgl_m);
}

TEST(DefaultMinAgl, LessWhereTheScenarioHasLessRoom) {
  // A goal in the air 2 m up: the default stays under it with the body (2 - 0.5 - 0.05).
  EXPECT_NEAR(default_min_agl_m(from_the_ground(50, 2)), 1.45, 1e-12);
  // A world 3 m high: the lift-off (default + body + margins) fits under its top.
  EXPECT_NEAR(default_min_agl_m(from_the_ground(3, 0)), 3 - 0.5 - 0.1, 1e-12);
  // A goal in the air lower than the body: no default at all.
  EXPECT_EQ(default_min_agl_m(from_the_ground(50, 0.4)), 0.0);
}

// mission.cruise_agl: the fleet's height for every UAV, airborne starts and min_agl given too;
// on a slope a point in the air leaves room to the ground within its body's reach, not only
// below it (the planners keep the body off the cell beside it, raised).
TEST(DefaultMinAgl, TheFleetsCruiseHeightGivesWayToTheGroundWithinReach) {
  Scenario airborne = from_the_ground(200, 100);
  airborne.uavs[0].start.z() = 100;
  airborne.uavs[0].min_agl_given = true;
  airborne.mission.cruise_agl_m = 30.0;
  EXPECT_DOUBLE_EQ(default_min_agl_m(airborne), 30.0);
  // Terrain rising 20 m a cell (10 m) east: the start at (10, 10) is 1 m from the 20 m cell.
  WorldSpec ws = airborne.world.spec();
  std::vector<double> h(20 * 20);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) h[j * 20 + i] = 20.0 * i;
  ws.terrain = TerrainGrid(Vec2(0, 0), 10.0, 20, 20, std::move(h));
  airborne.world = World(std::move(ws));
  airborne.uavs[0].goal = Vec3(185, 185, 410);  // 50 m above its cell and its neighbours
  airborne.uavs[0].start = Vec3(9, 10, 60);     // 60 m above its cell, 40 above the next 1 m away
  EXPECT_DOUBLE_EQ(default_min_agl_m(airborne), 30.0);
  airborne.uavs[0].start = Vec3(9.8, 10, 45);  // 25 m above the next cell 0.2 m away, within the body
  EXPECT_NEAR(default_min_agl_m(airborne), 45.0 - 20.0 - 0.5 - 0.05, 1e-9);
}

TEST(DefaultMinAgl, NoneWhereTheScenarioSaysOrNoOneTouchesTheGround) {
  Scenario given = from_the_ground(50, 0);
  given.uavs[0].min_agl_given = true;  // min_agl: 0 written: flown as written
  EXPECT_EQ(default_min_agl_m(given), 0.0);
  Scenario airborne = from_the_ground(50, 30);
  airborne.uavs[0].start.z() = 30;
  EXPECT_EQ(default_min_agl_m(airborne), 0.0);
  Scenario p5 = from_the_ground(50, 0);
  p5.mission.type = "formation_mission";  // a runway's take-offs, by P5's phases
  EXPECT_EQ(default_min_agl_m(p5), 0.0);
}

TEST(DefaultMinAgl, NoneWhereItWouldCloseATakeOffColumn) {
  // A balcony 2 m over the start: the take-off to 0.55 m clears it, one to 3.05 m does not.
  Scenario sc = from_the_ground(50, 0);
  WorldSpec ws = sc.world.spec();
  ws.obstacles.push_back(Box{Vec3(5, 5, 2), Vec3(15, 15, 2.5)});
  sc.world = World(std::move(ws));
  EXPECT_EQ(default_min_agl_m(sc), 0.0);
}

TEST(DefaultMinAgl, PlannersKeepIt) {
  Scenario sc = from_the_ground(50, 0);
  sc.default_min_agl_m = default_min_agl_m(sc);
  EXPECT_DOUBLE_EQ(planning_min_agl_m(sc), kDefaultMinAgl_m);
  EXPECT_DOUBLE_EQ(lift_height_m(sc, sc.uavs[0]), kDefaultMinAgl_m + 0.5 + 0.05);
  sc.uavs[0].min_agl_m = 10;  // a larger one set wins
  EXPECT_DOUBLE_EQ(planning_min_agl_m(sc), 10.0);
}

// A max_agl band whose top rises above the world's bounds over high ground: the sky there is
// outside the world already, so the planners' world closes only the rest (no empty box).
TEST(PlanningView, BandTopAboveTheBoundsClosesNothingThere) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 100, 100)};
  ws.terrain = TerrainGrid(Vec2(0, 0), 100.0, 2, 1, {10.0, 90.0});  // a low and a high cell
  Scenario sc;
  sc.world = World(std::move(ws));
  UavSpec u;
  u.id = "u1";
  u.start = Vec3(50, 50, 30);
  u.goal = Vec3(150, 50, 95);
  u.max_agl_m = 40.0;
  sc.uavs.push_back(u);
  const PlanningView v = planning_view(sc);
  const World& w = v.scenario.world;
  EXPECT_TRUE(w.point_collides(Vec3(50, 50, 60), 1.0));    // above the band over the low cell
  EXPECT_FALSE(w.point_collides(Vec3(150, 50, 99), 1.0));  // the high cell's band reaches the top
  EXPECT_FALSE(w.point_collides(Vec3(50, 50, 40), 1.0));
}

}  // namespace
}  // namespace uavplan
