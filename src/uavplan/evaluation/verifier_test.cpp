// The verifier catches every violation class: each test crafts a plan with one defect.
#include "uavplan/evaluation/verifier.h"
#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/coordination/rendezvous/rendezvous_mission.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "uavplan/coordination/contract/arrival_points.h"

namespace uavplan {
namespace {

Scenario base_scenario() {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 100, 50)};
  ws.obstacles.push_back(Box{Vec3(40, 40, 0), Vec3(60, 60, 30)});
  ws.terrain = TerrainGrid(Vec2(0, 0), 50.0, 2, 2, {0.0, 10.0, 0.0, 0.0});  // a 10 m plateau at x in [50,100), y < 50
  ws.moving.push_back({"m1", 2.0, Vec3(20, 90, 40), Vec3(0, 0, 0)});        // parked at (20, 90, 40)
  Scenario sc;
  sc.name = "verifier";
  sc.world = World(std::move(ws));
  for (int i = 0; i < 2; ++i) {
    UavSpec u;
    u.id = i == 0 ? "a" : "b";
    u.start = i == 0 ? Vec3(10, 10, 20) : Vec3(10, 20, 20);
    u.goal = i == 0 ? Vec3(30, 10, 20) : Vec3(30, 20, 20);
    u.radius_m = 0.5;
    u.speed = {0, 5, 5};
    u.max_turn_rad = deg_to_rad(60);
    u.max_climb_rad = deg_to_rad(30);
    u.ceiling_m = 45;
    sc.uavs.push_back(u);
  }
  sc.mission.separation_m = 3.0;
  return sc;
}

Plan base_plan(const Scenario& sc) {
  Plan p;
  p.scenario = sc.name;
  p.status = Status::solved;
  for (const auto& u : sc.uavs) {
    UavPlan up;
    up.id = u.id;
    up.status = Status::solved;
    up.waypoints = {u.start, *u.goal};
    up.trajectory = time_route(up.waypoints, 5.0, 0.0, 1.0);
    p.uavs.push_back(up);
  }
  return p;
}

std::vector<ViolationKind> kinds(const Scenario& sc, const Plan& p, const std::string& only_uav = "") {
  std::vector<ViolationKind> k;
  for (const auto& v : verify_plan(sc, p))
    if (only_uav.empty() || v.uav == only_uav) k.push_back(v.kind);
  return k;
}

void fly(Plan& p, int uav, std::vector<Vec3> pts, double speed = 5.0, double depart = 0.0) {
  p.uavs[uav].waypoints = pts;
  p.uavs[uav].trajectory = time_route(pts, speed, depart, 1.0);
}

using K = ViolationKind;
using ::testing::ElementsAre;

TEST(Verifier, CleanPlanHolds) {
  const Scenario sc = base_scenario();
  EXPECT_TRUE(verify_plan(sc, base_plan(sc)).empty());
}

TEST(Verifier, Bounds) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {10, -5, 20}, {30, 10, 20}});
  EXPECT_EQ(kinds(sc, p).front(), K::bounds);
}

TEST(Verifier, StaticObstacleWithTimeAndPlace) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {50, 50, 20}, {30, 10, 20}});
  const auto v = verify_plan(sc, p);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v[0].kind, K::obstacle);
  EXPECT_EQ(v[0].uav, "a");
  ASSERT_TRUE(v[0].t_s && v[0].where);
  EXPECT_NEAR(v[0].where->x(), v[0].where->y(), 1e-6);  // on the diagonal into the box
  EXPECT_NE(v[0].message.find("to obstacle 0 (box)"), std::string::npos) << v[0].message;  // which one
}

TEST(Verifier, Terrain) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {40, 20, 5.2}, {70, 20, 5.2}, {30, 10, 20}});  // 5.2 m over a 10 m plateau
  bool terrain_hit = false;
  for (const auto& v : verify_plan(sc, p))
    terrain_hit |=
        v.kind == K::obstacle && v.where && v.where->x() >= 49.0 && v.message.find("the terrain") != std::string::npos;
  EXPECT_TRUE(terrain_hit);
}

TEST(Verifier, MovingObstacle) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {20, 80, 40}, {20, 95, 40}, {30, 10, 20}}, 5.0);
  bool hit = false;
  for (const auto k : kinds(sc, p)) hit |= k == K::moving_obstacle;
  EXPECT_TRUE(hit);
}

TEST(Verifier, SeparationAtEqualTimes) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 1, {{10, 20, 20}, {10, 12, 20}, {30, 12, 20}, {30, 20, 20}});  // flies 2 m beside a
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::separation));
  // The same path flown after a has arrived is fine: equal times, not equal places, count.
  fly(p, 1, {{10, 20, 20}, {10, 14, 20}, {34, 14, 20}, {30, 20, 20}}, 5.0, 0.0);
  const auto k = kinds(sc, p);
  EXPECT_EQ(std::count(k.begin(), k.end(), K::separation), 0);
}

TEST(Verifier, TurnAndClimbAndStartHeading) {
  Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {20, 10, 20}, {20, 5, 20}, {30, 10, 20}});  // 90 deg turn
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::turn));
  fly(p, 0, {{10, 10, 20}, {20, 10, 30}, {30, 10, 20}});  // 45 deg climb
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::climb));
  sc.uavs[0].heading_rad = kPi;  // facing west, first segment east
  EXPECT_THAT(kinds(sc, base_plan(sc)), ::testing::Contains(K::turn));
}

TEST(Verifier, SpeedAndCeiling) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {30, 10, 20}}, 6.0);
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::speed));
  fly(p, 0, {{10, 10, 20}, {12, 10, 21}, {80, 10, 47}, {10, 10, 47}, {30, 10, 20}});
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::ceiling));
}

TEST(Verifier, StartAndGoal) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{11, 10, 20}, {29, 10, 20}});
  EXPECT_THAT(kinds(sc, p), ::testing::ElementsAre(K::start, K::goal));
}

TEST(Verifier, ViaPointsInOrder) {
  Scenario sc = base_scenario();
  sc.mission.type = "route";
  sc.mission.waypoints = {{20, 30, 20}, {20, 10, 20}};
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {20, 10, 20}, {20, 30, 20}, {30, 10, 20}});  // visits them reversed
  EXPECT_THAT(kinds(sc, p, "a"), ::testing::Contains(K::via_point));
  fly(p, 0, {{10, 10, 20}, {20, 30, 20}, {20, 10, 20}, {30, 10, 20}});
  EXPECT_THAT(kinds(sc, p, "a"), ::testing::Not(::testing::Contains(K::via_point)));
  EXPECT_THAT(kinds(sc, p, "b"), ::testing::Contains(K::via_point));  // b flies straight past them
}

TEST(Verifier, RendezvousLengthSpread) {
  Scenario sc = base_scenario();
  sc.mission.type = "rendezvous";
  sc.mission.edit_section<RendezvousSection>().arrival_tolerance_m = 1.0;
  Plan p = base_plan(sc);
  fly(p, 1, {{10, 20, 20}, {20, 30, 20}, {30, 20, 20}});  // 28.3 m against 20 m
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::length_spread));
}

TEST(Verifier, MissingAndUnknownUavs) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  p.uavs[1].id = "zzz";
  EXPECT_THAT(kinds(sc, p), ::testing::ElementsAre(K::unknown_uav, K::not_planned));
  p = base_plan(sc);
  p.uavs[0].trajectory.clear();
  EXPECT_THAT(kinds(sc, p), ::testing::ElementsAre(K::not_planned));
}

TEST(Verifier, TimeGoingBackwards) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  std::swap(p.uavs[0].trajectory[1].t_s, p.uavs[0].trajectory[2].t_s);
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::trajectory));
}

TEST(Verifier, FinalizeFailsViolatingUavs) {
  const Scenario sc = base_scenario();
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {50, 50, 20}, {30, 10, 20}});
  finalize_plan(sc, p);
  EXPECT_EQ(p.uavs[0].status, Status::failed);
  EXPECT_EQ(p.uavs[1].status, Status::solved);
  EXPECT_EQ(p.status, Status::partial);
  EXPECT_NE(p.uavs[0].message.find("obstacle"), std::string::npos);
}

// A UAV standing on the ground takes off and lands vertically: the climb limit, min_agl and the
// ground under it do not count on those legs; obstacles and the terrain beside the column do.
TEST(Verifier, TakeOffAndLandingLegs) {
  Scenario sc = base_scenario();
  sc.uavs.resize(1);
  UavSpec& u = sc.uavs[0];
  u.start = Vec3(10, 10, 0);
  u.goal = Vec3(30, 10, 0);
  u.min_agl_m = 5;
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 0}, {10, 10, 2}, {10, 10, 20}, {30, 10, 20}, {30, 10, 0}});
  EXPECT_TRUE(verify_plan(sc, p).empty()) << describe(verify_plan(sc, p).front());
  // Airborne, the same height is low: a hop at 2 m between two columns.
  fly(p, 0, {{10, 10, 0}, {10, 10, 20}, {20, 10, 2}, {30, 10, 20}, {30, 10, 0}});
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::low_altitude));
  // A column beside the 10 m plateau (x >= 50, y < 50) scrapes it above the UAV's radius.
  u.goal = Vec3(49.8, 10, 0);
  fly(p, 0, {{10, 10, 0}, {10, 10, 20}, {49.8, 10, 20}, {49.8, 10, 0}});
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::obstacle));
}

// max_agl: the height above the ground under the whole segment, exactly: a level flight at 20 m
// holds 15 m over the 10 m plateau and breaks it over the floor beside it; take-off legs are
// not in the band.
TEST(Verifier, MaxAglOverTheGroundUnderTheSegment) {
  Scenario sc = base_scenario();
  sc.uavs.resize(1);
  UavSpec& u = sc.uavs[0];
  u.max_turn_rad = kPi;
  u.start = Vec3(60, 10, 20);
  u.goal = Vec3(95, 10, 20);
  u.max_agl_m = 15;
  Plan p = base_plan(sc);
  fly(p, 0, {{60, 10, 20}, {95, 10, 20}});  // over the plateau: 10 m above it
  EXPECT_TRUE(verify_plan(sc, p).empty()) << describe(verify_plan(sc, p).front());
  u.start = Vec3(45.0, 10, 20);  // from beside the plateau, 20 m above the floor there
  fly(p, 0, {{45.0, 10, 20}, {95, 10, 20}});
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::high_altitude));
  // Both ends in the band (14 m over the plateau, 14 m over the floor), the middle not: where it
  // leaves the plateau at x = 50 it is 19 m above the floor.
  u.start = Vec3(60, 10, 24);
  u.goal = Vec3(40, 10, 14);
  fly(p, 0, {{60, 10, 24}, {40, 10, 14}});
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::high_altitude));
  // Up from the ground to 30 m and along at 12 m above it: the take-off leg is not in the band.
  u.start = Vec3(10, 10, 0);
  u.goal = Vec3(30, 10, 12);
  fly(p, 0, {{10, 10, 0}, {10, 10, 30}, {10, 10, 12}, {30, 10, 12}});
  EXPECT_THAT(kinds(sc, p), ::testing::Not(::testing::Contains(K::high_altitude)));
}

TEST(Verifier, ClearanceAndMinAgl) {
  Scenario sc = base_scenario();
  sc.uavs.resize(1);
  sc.uavs[0].max_turn_rad = kPi;
  Plan p = base_plan(sc);
  fly(p, 0, {{10, 10, 20}, {38.5, 45, 20}, {30, 10, 20}});  // 1.5 m from the box (x >= 40)
  for (const auto& v : verify_plan(sc, p)) ADD_FAILURE() << describe(v);
  sc.uavs[0].clearance_m = 2;
  const auto v = verify_plan(sc, p);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v[0].kind, K::obstacle);
  EXPECT_NE(v[0].message.find("radius plus clearance 2.5 m"), std::string::npos) << v[0].message;
  sc.uavs[0].clearance_m = 0;
  sc.uavs[0].min_agl_m = 25;  // flies at 20 m
  EXPECT_THAT(kinds(sc, base_plan(sc), "a"), ::testing::Contains(K::low_altitude));
}

// UAVs sent to one goal keep their separation there too; each may end anywhere within its
// arrival point's distance of the goal (arrival_points.h), not further.
TEST(Verifier, SharedGoalsAreNoExemption) {
  Scenario sc = base_scenario();
  sc.uavs[1].goal = sc.uavs[0].goal;
  Plan p = base_plan(sc);
  EXPECT_THAT(kinds(sc, p), ::testing::Contains(K::separation));
  const std::vector<Arrival> at = arrival_points(sc);
  ASSERT_GT(at[0].tolerance_m, 0.0);
  for (int i = 0; i < 2; ++i) fly(p, i, {sc.uavs[i].start, at[i].point});
  EXPECT_TRUE(verify_plan(sc, p).empty()) << describe(verify_plan(sc, p).front());
  fly(p, 1, {sc.uavs[1].start, *sc.uavs[1].goal + Vec3(0, 3 * at[1].tolerance_m, 0)});
  EXPECT_THAT(kinds(sc, p, "b"), ::testing::Contains(K::goal));
}

// A formation's arrival (contract): at the goal to stay. One that hovers at its goal while its
// mate comes arrived early, though both trajectories end together; the spread of the arrivals
// is held against arrival_tolerance_s.
TEST(Verifier, FormationArrivalsAreAtTheGoalToStay) {
  Scenario sc = base_scenario();
  sc.mission.type = "formation";
  sc.mission.edit_section<FormationSection>().shape = {{0, 0, 0}, {0, 10, 0}};
  sc.mission.edit_section<FormationSection>().arrival_tolerance_s = 2.0;
  Plan p = base_plan(sc);  // both fly 20 m at 5 m/s: arrive at 4 s
  EXPECT_TRUE(kinds(sc, p).empty());
  fly(p, 1, {{10, 20, 20}, {30, 20, 20}}, 5.0, 10.0);        // b leaves at 10 s: arrives at 14 s
  p.uavs[0].trajectory.push_back({14.0, *sc.uavs[0].goal});  // a hovers at its goal until then
  EXPECT_THAT(kinds(sc, p), ElementsAre(K::arrival_spread));
  fly(p, 0, {{10, 10, 20}, {30, 10, 20}}, 5.0, 9.0);  // a leaves at 9 s: 1 s apart
  EXPECT_TRUE(kinds(sc, p).empty());
}

}  // namespace
}  // namespace uavplan
