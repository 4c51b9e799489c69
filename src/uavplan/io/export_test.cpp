#include "uavplan/io/export.h"

#include <gtest/gtest.h>
#include <GeographicLib/Geodesic.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>

#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/gis_export.h"
#include "uavplan/io/io_test_fixtures.h"
#include "uavplan/io/mission_items.h"
#include "uavplan/io/qgc_export.h"

namespace uavplan {
namespace {

using test::plan_of;
using test::sample_uav;
using test::scenario_with;

// The one UAV of the sample plan as exported, which must hold.
ExportedUav exported(const Scenario& sc, const ExportOptions& opt = {}, UavPlan u = sample_uav()) {
  const VerifiedExport v = verified_export(sc, plan_of({std::move(u)}), opt);
  EXPECT_TRUE(v.holds()) << (v.left_out.empty() ? "" : v.left_out.front());
  if (v.uavs.size() != 1) throw std::runtime_error("not exported");
  return v.uavs.front();
}

std::vector<int> commands(const std::vector<MissionItem>& items) {
  std::vector<int> c;
  c.reserve(items.size());
  for (const auto& it : items) c.push_back(it.command);
  return c;
}

TEST(GeoFrame, RoundTripAndKnownScale) {
  const GeoFrame f(GeoOrigin{47.3977, 8.5456, 488.0});
  const LatLonAlt o = f.to_wgs84(Vec3::Zero());
  EXPECT_NEAR(o.lat_deg, 47.3977, 1e-12);
  EXPECT_NEAR(o.lon_deg, 8.5456, 1e-12);
  EXPECT_NEAR(o.alt_m, 488.0, 1e-9);
  // One kilometre north at 47.4 deg N is 1/111.18 of a degree of latitude (WGS84 meridian arc).
  const LatLonAlt n = f.to_wgs84(Vec3(0, 1000, 0));
  EXPECT_NEAR((n.lat_deg - 47.3977) * 111'180.0, 1000.0, 1.0);
  EXPECT_NEAR(n.lon_deg, 8.5456, 1e-9);
  const LatLonAlt e = f.to_wgs84(Vec3(1000, 0, 0));
  EXPECT_GT(e.lon_deg, 8.5456);
  const Vec3 p(123.4, -567.8, 42.0);
  const LatLonAlt g = f.to_wgs84(p);
  EXPECT_LT((f.to_local(g.lat_deg, g.lon_deg, g.alt_m) - p).norm(), 1e-6);
}

TEST(GeoFrame, AltitudeIsOriginPlusLocalHeightEvenFarAway) {
  // P4's world reaches 65 km from its origin: the tangent plane is 330 m above the datum there,
  // but a route at z = 100 m flies at origin.alt + 100 m.
  const GeoFrame f(GeoOrigin{30.0, 110.0, 500.0});
  for (const Vec3& p : {Vec3(65000, 0, 100), Vec3(-40000, 50000, 100), Vec3(2000, 0, 0)}) {
    const LatLonAlt g = f.to_wgs84(p);
    EXPECT_DOUBLE_EQ(g.alt_m, 500.0 + p.z());
    EXPECT_LT((f.to_local(g.lat_deg, g.lon_deg, g.alt_m) - p).norm(), 1e-6) << p.transpose();
  }
  // Horizontally: 65 km east is 65 km along the ground (to within the tangent plane's 1 m).
  const LatLonAlt e = f.to_wgs84(Vec3(65000, 0, 100));
  EXPECT_NEAR((e.lon_deg - 110.0) * 111'320.0 * std::cos(30.0 * kPi / 180.0), 65000.0, 150.0);
}

TEST(GeoFrame, KeepsDistancesOverLargeAreas) {
  // P5's mission reaches 900 km from its origin: the distance and bearing from the origin are
  // exact, and a 1 km leg across the bearing is at most rho^2 / (6 R^2) shorter, never longer.
  const GeoFrame f(GeoOrigin{46.8, 8.2, 500.0});
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const double rho = 900'000.0, R = 6'371'000.0;
  for (const double bearing_deg : {0.0, 45.0, 135.0, 250.0}) {
    const double b = bearing_deg * kPi / 180.0;
    const Vec3 p(rho * std::sin(b), rho * std::cos(b), 0.0);
    const LatLonAlt a = f.to_wgs84(p);
    double s12 = 0, azi1 = 0, azi2 = 0;
    g.Inverse(46.8, 8.2, a.lat_deg, a.lon_deg, s12, azi1, azi2);
    EXPECT_NEAR(s12, rho, 1e-3) << bearing_deg;
    EXPECT_NEAR(std::remainder(azi1 - bearing_deg, 360.0), 0.0, 1e-9) << bearing_deg;
    const Vec3 across = p + 1000.0 * Vec3(std::cos(b), -std::sin(b), 0.0);
    const LatLonAlt c = f.to_wgs84(across);
    g.Inverse(a.lat_deg, a.lon_deg, c.lat_deg, c.lon_deg, s12);
    EXPECT_LE(s12, 1000.0 + 1e-3) << bearing_deg;
    EXPECT_GE(s12, 1000.0 * (1.0 - 1.01 * rho * rho / (6.0 * R * R))) << bearing_deg;
    EXPECT_LT((f.to_local(c.lat_deg, c.lon_deg, c.alt_m) - across).norm(), 1e-6);
  }
}

TEST(GeoFrame, ExportSaysHowMuchFarDistancesShrink) {
  Scenario sc = scenario_with();
  sc.origin = GeoOrigin{46.8, 8.2, 500.0};
  VerifiedExport flights;
  flights.uavs.emplace_back();
  flights.uavs.back().plan.trajectory = {{0.0, Vec3(0, 0, 100)}, {100.0, Vec3(50'000, 0, 100)}};
  EXPECT_TRUE(frame_notes(sc, flights).empty());  // 0.001 %
  flights.uavs.back().plan.trajectory.push_back({6000.0, Vec3(600'000, 700'000, 100)});
  const std::vector<std::string> notes = frame_notes(sc, flights);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("922 km"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("0.35 %"), std::string::npos) << notes[0];
}

TEST(Export, MissionFollowsTheTrajectory) {
  const Scenario sc = scenario_with();
  const auto items = mission_items(sc, exported(sc), {});
  // takeoff, the 4 s hold, the planned speed, one waypoint for the collinear east legs, the speed
  // change, north, land.
  EXPECT_EQ(commands(items), (std::vector<int>{kCmdTakeoff, kCmdLoiterTime, kCmdChangeSpeed, kCmdWaypoint,
                                               kCmdChangeSpeed, kCmdWaypoint, kCmdLand}));
  EXPECT_DOUBLE_EQ(items[1].params[0], 4.0);
  EXPECT_DOUBLE_EQ(items[2].params[0], 1.0);  // multirotor: ground speed
  EXPECT_DOUBLE_EQ(items[2].params[1], 5.0);  // commanded before the first leg
  EXPECT_DOUBLE_EQ(items[4].params[1], 10.0);
  EXPECT_NEAR(items[0].params[6], 10.0, 1e-3);  // takeoff to the start's height above home
  EXPECT_NEAR(items[3].params[3], 90.0, 1e-6);  // east is compass yaw 90
  EXPECT_NEAR(items[5].params[3], 0.0, 1e-6);   // north is 0
  EXPECT_NEAR(items[6].params[6], 0.0, 1e-9);   // lands on the ground under its goal
  const GeoFrame f(*sc.origin);
  const LatLonAlt end = f.to_wgs84(Vec3(100, 100, 10));
  EXPECT_NEAR(items[5].params[4], end.lat_deg, 1e-9);
  EXPECT_NEAR(items[5].params[5], end.lon_deg, 1e-9);
  EXPECT_EQ(items[4].frame, kFrameMission);  // DO commands carry no position
  for (const auto& it : items)
    if (it.command != kCmdChangeSpeed) {
      EXPECT_EQ(it.frame, kFrameGlobalRelativeAlt);
    }
}

TEST(Export, SpeedChangesBelowTenPercentMerge) {
  const Scenario sc = scenario_with();
  UavPlan u = sample_uav();  // east at 5, 5.4 and 4.7 m/s, then north at 5.2 m/s
  u.trajectory = {{0.0, Vec3(0, 0, 10)},
                  {10.0, Vec3(50, 0, 10)},
                  {20.0, Vec3(104, 0, 10)},
                  {30.0, Vec3(151, 0, 10)},
                  {40.0, Vec3(151, 52, 10)}};
  EXPECT_EQ(commands(mission_items(sc, exported(sc, {}, u), {})),
            (std::vector<int>{kCmdTakeoff, kCmdChangeSpeed, kCmdWaypoint, kCmdWaypoint, kCmdLand}));
  u.trajectory.back() = {40.0, Vec3(151, 60, 10)};  // 6 m/s: 20 % faster
  EXPECT_EQ(commands(mission_items(sc, exported(sc, {}, u), {})),
            (std::vector<int>{kCmdTakeoff, kCmdChangeSpeed, kCmdWaypoint, kCmdChangeSpeed, kCmdWaypoint, kCmdLand}));
  ExportOptions fixed_wing;
  fixed_wing.vehicle = VehicleKind::fixed_wing;
  EXPECT_DOUBLE_EQ(mission_items(sc, exported(sc, {}, u), fixed_wing)[1].params[0], 0.0);  // airspeed
}

// Legs a little faster than the current speed keep it only while the time gained stays within
// speed_drift_s (0.5 s): at 5 m/s, a 54 m leg planned in 10 s would arrive 0.8 s late.
TEST(Export, SpeedKeptOnlyWhileTheDriftStaysSmall) {
  const Scenario sc = scenario_with();
  UavPlan u = sample_uav();  // east at 5 m/s, then a zigzag at 5.4 m/s
  u.trajectory = {{0.0, Vec3(0, 0, 10)},
                  {10.0, Vec3(50, 0, 10)},
                  {20.0, Vec3(50, 54, 10)},
                  {30.0, Vec3(104, 54, 10)},
                  {40.0, Vec3(104, 108, 10)}};
  const auto items = mission_items(sc, exported(sc, {}, u), {});
  EXPECT_EQ(commands(items), (std::vector<int>{kCmdTakeoff, kCmdChangeSpeed, kCmdWaypoint, kCmdChangeSpeed,
                                               kCmdWaypoint, kCmdWaypoint, kCmdWaypoint, kCmdLand}));
  EXPECT_NEAR(items[3].params[1], 5.4, 1e-9);
}

// ArduCopter flies WPNAV_SPEED horizontally (a climb on top): a leg climbing 40 m over 30 m in
// 10 s is commanded 3 m/s there, 5 m/s (along the leg) for PX4.
TEST(Export, ArduCopterSpeedsAreHorizontal) {
  const Scenario sc = scenario_with();
  UavPlan u = sample_uav();
  u.trajectory = {{0.0, Vec3(0, 0, 10)}, {10.0, Vec3(30, 0, 50)}};
  ExportOptions copter;
  copter.firmware = Firmware::ardupilot;
  EXPECT_NEAR(mission_items(sc, exported(sc, copter, u), copter)[1].params[1], 3.0, 1e-9);
  EXPECT_NEAR(mission_items(sc, exported(sc, {}, u), {})[1].params[1], 5.0, 1e-9);
}

// A hold between two legs at 5 m/s: ArduCopter stops and starts on its S-curves (0.625 s of lag
// each) and rests 1.3 s on the waypoint, so it loiters 10 - 2.55 s; PX4 the plan's 10 s.
TEST(Export, ArduCopterHoldsLessTheStopAndTheStart) {
  const Scenario sc = scenario_with();
  UavPlan u = sample_uav();
  u.trajectory = {{0.0, Vec3(0, 0, 10)}, {10.0, Vec3(50, 0, 10)}, {20.0, Vec3(50, 0, 10)}, {30.0, Vec3(50, 50, 10)}};
  const auto loiter_s = [&](const ExportOptions& opt) {
    for (const MissionItem& it : mission_items(sc, exported(sc, opt, u), opt))
      if (it.command == kCmdLoiterTime) return it.params[0];
    return -1.0;
  };
  ExportOptions copter;
  copter.firmware = Firmware::ardupilot;
  EXPECT_NEAR(loiter_s(copter), 10.0 - 2.0 * 0.625 - 1.3, 1e-3);
  EXPECT_NEAR(loiter_s({}), 10.0, 1e-9);
}

// ArduCopter takes up a new speed only on a long leg (docs/decisions/0020): a zigzag of 10 m legs
// at 4 and 5 m/s after a 50 m leg is flown as one stretch at its mean speed, retimed within a
// second of the plan's clock, one speed commanded; PX4 keeps the plan's speed changes.
TEST(Export, ArduCopterFliesShortLegsAtOneSpeed) {
  const Scenario sc = scenario_with();
  UavPlan u = sample_uav();
  u.trajectory = {{0.0, Vec3(0, 0, 10)}, {10.0, Vec3(50, 0, 10)}};
  for (int k = 1; k <= 6; ++k) {
    const Vec3 step(10.0 * std::cos(k % 2 ? 0.5 : -0.5), 10.0 * std::sin(k % 2 ? 0.5 : -0.5), 0.0);
    u.trajectory.push_back({u.trajectory.back().t_s + (k % 2 ? 2.5 : 2.0), u.trajectory.back().p + step});
  }
  const auto speeds = [&](const ExportOptions& opt) {
    std::vector<double> v;
    for (const MissionItem& it : mission_items(sc, exported(sc, opt, u), opt))
      if (it.command == kCmdChangeSpeed) v.push_back(it.params[1]);
    return v;
  };
  ExportOptions copter;
  copter.firmware = Firmware::ardupilot;
  const ExportedUav e = exported(sc, copter, u);
  ASSERT_EQ(e.body_end + 1, u.trajectory.size());  // the landing after it
  double length_m = 0.0;
  for (std::size_t k = 1; k < u.trajectory.size(); ++k) {
    length_m += (u.trajectory[k].p - u.trajectory[k - 1].p).norm();
    const double share = length_m / 110.0;  // every row on one clock: 110 m in the plan's 23.5 s
    EXPECT_NEAR(e.plan.trajectory[k].t_s, 23.5 * share, 1e-9) << k;
    EXPECT_LE(std::abs(e.plan.trajectory[k].t_s - u.trajectory[k].t_s) * 5.0, 5.0) << k;
  }
  const std::vector<double> copter_speeds = speeds(copter);
  ASSERT_EQ(copter_speeds.size(), 1u);
  EXPECT_NEAR(copter_speeds[0], 110.0 / 23.5, 1e-3);
  EXPECT_GT(speeds({}).size(), 2u);
}

TEST(Export, EveryEndIsFlownAndVerified) {
  const Scenario sc = scenario_with();
  ExportOptions opt;
  opt.end = MissionEnd::rtl;
  ExportedUav e = exported(sc, opt);
  auto items = mission_items(sc, e, opt);
  EXPECT_EQ(items.back().command, kCmdReturn);
  EXPECT_EQ(items.back().frame, kFrameMission);
  EXPECT_EQ(items[items.size() - 2].command, kCmdWaypoint);  // above home, at the goal's height
  EXPECT_NEAR(items[items.size() - 2].params[6], 10.0, 1e-3);
  EXPECT_EQ(e.plan.trajectory.back().p, Vec3(0, 0, 0));  // the return and the descent are in the flight
  opt.end = MissionEnd::loiter;
  items = mission_items(sc, exported(sc, opt), opt);
  EXPECT_EQ(items.back().command, kCmdLoiterUnlimited);
  EXPECT_EQ(items.back().params[2], 0.0);
  opt.end = MissionEnd::none;
  EXPECT_EQ(mission_items(sc, exported(sc, opt), opt).back().command, kCmdWaypoint);
  // A return that would cross a tall wall is refused, naming the leg.
  const Scenario walled = scenario_with({Box{Vec3(40, 20, 0), Vec3(60, 80, 100)}});
  opt.end = MissionEnd::rtl;
  const VerifiedExport v = verified_export(walled, plan_of({sample_uav()}), opt);
  ASSERT_EQ(v.left_out.size(), 1u);
  EXPECT_NE(v.left_out[0].find("rtl legs"), std::string::npos) << v.left_out[0];
  EXPECT_NE(v.left_out[0].find("obstacle"), std::string::npos) << v.left_out[0];
  EXPECT_TRUE(v.uavs.empty());
}

TEST(Export, FixedWingLandsOnAGlideOrCircles) {
  Scenario sc = scenario_with();
  sc.world = World(WorldSpec{Aabb{Vec3(-1000, -1000, 0), Vec3(1000, 1000, 100)}, {}, {}, {}, {}, {}, {}});
  ExportOptions opt;
  opt.vehicle = VehicleKind::fixed_wing;
  ExportedUav e = exported(sc, opt);
  const auto items = mission_items(sc, e, opt);
  EXPECT_EQ(commands(items), (std::vector<int>{kCmdTakeoff, kCmdLoiterTime, kCmdChangeSpeed, kCmdWaypoint,
                                               kCmdChangeSpeed, kCmdLandStart, kCmdWaypoint, kCmdLand}));
  EXPECT_DOUBLE_EQ(items[2].params[0], 0.0);   // fixed wing: airspeed
  EXPECT_DOUBLE_EQ(items[0].params[0], 10.0);  // NAV_TAKEOFF's minimum pitch: the verified climb-out
  ASSERT_TRUE(e.touchdown && e.approach);
  EXPECT_EQ(*e.approach, Vec3(100, 100, 10));
  EXPECT_NEAR(e.touchdown->y() - 100, 10.0 / std::tan(deg_to_rad(4.9)), 1e-6);  // straight on, 4.9 degrees
  EXPECT_NEAR(e.home.x(), -10.0 / std::tan(deg_to_rad(10.0)), 1e-6);            // climb-out behind the start
  EXPECT_NEAR(e.home.y(), 0.0, 1e-9);
  opt.end = MissionEnd::loiter;
  EXPECT_EQ(mission_items(sc, exported(sc, opt), opt).back().params[2], 80.0);
  opt.firmware = Firmware::ardupilot;
  EXPECT_EQ(mission_items(sc, exported(sc, opt), opt).back().params[2], 60.0);
  // A fixed wing cannot fly a vertical take-off from the ground.
  UavPlan ground = sample_uav();
  sc.uavs[0].start = Vec3(0, 0, 0);
  ground.trajectory.insert(ground.trajectory.begin(), {0.0, Vec3(0, 0, 0)});
  for (std::size_t k = 1; k < ground.trajectory.size(); ++k) ground.trajectory[k].t_s += 2.0;
  const VerifiedExport v = verified_export(sc, plan_of({ground}), opt);
  ASSERT_EQ(v.left_out.size(), 1u);
  EXPECT_NE(v.left_out[0].find("cannot fly its planned vertical take-off"), std::string::npos) << v.left_out[0];
}

// A flat (2-D) world's plan flies at the flat altitude: the take-off climbs to it above home,
// the route is the plan's at that height, the landing comes down from it; a fixed wing is refused.
TEST(Export, AFlatWorldsPlanFliesAtTheFlatAltitude) {
  Scenario sc = scenario_with();
  WorldSpec w;
  w.bounds = Aabb{Vec3(0, 0, 0), Vec3(1000, 1000, 0)};
  sc.world = World(std::move(w));
  sc.uavs[0].start = Vec3::Zero();
  UavPlan u = sample_uav();
  for (TrajectorySample& row : u.trajectory) row.p.z() = 0.0;
  ExportOptions opt;
  opt.flat_altitude_m = 25.0;
  const ExportedUav e = exported(sc, opt, u);
  EXPECT_DOUBLE_EQ(e.home.z(), 0.0);
  EXPECT_DOUBLE_EQ(e.takeoff_to.z(), 25.0);
  const Trajectory& tr = e.plan.trajectory;
  for (std::size_t k = 0; k <= e.body_end; ++k) EXPECT_DOUBLE_EQ(tr[k].p.z(), 25.0) << k;
  EXPECT_EQ(tr.back().p, Vec3(100, 100, 0));
  EXPECT_GT(tr.back().t_s, 34.0);
  const std::vector<MissionItem> items = mission_items(sc, e, opt);
  EXPECT_EQ(items.front().command, kCmdTakeoff);
  EXPECT_NEAR(items.front().params[6], 25.0, 1e-9);
  EXPECT_EQ(items.back().command, kCmdLand);
  opt.vehicle = VehicleKind::fixed_wing;
  const VerifiedExport fw = verified_export(sc, plan_of({u}), opt);
  ASSERT_EQ(fw.left_out.size(), 1u);
  EXPECT_NE(fw.left_out[0].find("flat (2-D)"), std::string::npos) << fw.left_out[0];
  // Without an autopilot's file (csv, geojson, kml) it is written as planned, saying why.
  opt.autopilot = false;
  const VerifiedExport gis = verified_export(sc, plan_of({u}), opt);
  EXPECT_TRUE(gis.holds());
  ASSERT_EQ(gis.uavs.size(), 1u);
  EXPECT_EQ(gis.uavs[0].plan.trajectory.size(), u.trajectory.size());
  ASSERT_EQ(gis.notes.size(), 1u);
  EXPECT_NE(gis.notes[0].find("flat (2-D)"), std::string::npos) << gis.notes[0];
}

// A vertical take-off blocked below the start (a roof under it) goes up beside it, from the
// nearest clear spot, and flies level to the start; the mission says so with a waypoint there.
TEST(Export, ABlockedTakeOffGoesUpBesideTheStart) {
  const Scenario sc = scenario_with({Box{Vec3(-5, -5, 0), Vec3(3, 3, 6)}});
  const ExportedUav e = exported(sc);
  EXPECT_NEAR(e.home.z(), 0.0, 1e-9);
  EXPECT_GT(e.home.head<2>().norm(), 3.0);
  EXPECT_DOUBLE_EQ(e.takeoff_to.z(), 10.0);
  const std::vector<MissionItem> items = mission_items(sc, e, {});
  ASSERT_GE(items.size(), 3u);
  EXPECT_EQ(items[0].command, kCmdTakeoff);
  EXPECT_EQ(items[1].command, kCmdChangeSpeed);
  EXPECT_EQ(items[2].command, kCmdWaypoint);
  const LatLonAlt start = GeoFrame(*sc.origin).to_wgs84(Vec3(0, 0, 10));
  EXPECT_NEAR(items[2].params[4], start.lat_deg, 1e-8);
  EXPECT_NEAR(items[2].params[5], start.lon_deg, 1e-8);
  const Trajectory rows = exported_rows(e);
  EXPECT_EQ(rows[0].p, e.home);
  EXPECT_EQ(rows[1].p, e.takeoff_to);
  EXPECT_EQ(rows[2].p, Vec3(0, 0, 10));
  EXPECT_DOUBLE_EQ(rows[2].t_s, 0.0);
}

// A goal beside a terrain step (an elevation model's cells are steps): the landing straight
// down would scrape the higher cell; it flies level to the nearest clear column and lands there,
// which NAV_LAND at that position flies (issue: real terrain).
TEST(Export, ABlockedLandingComesDownBesideTheGoal) {
  Scenario sc = scenario_with();
  WorldSpec w = sc.world.spec();
  std::vector<double> h(400, 0.0);
  h[1 * 20 + 1] = 9.0;  // x, y in [50, 100): its corner is under the goal (100, 100, 10)
  w.terrain = TerrainGrid(Vec2(0, 0), 50.0, 20, 20, h);
  sc.world = World(std::move(w));
  const ExportedUav e = exported(sc);
  ASSERT_TRUE(e.touchdown);
  EXPECT_NEAR(e.touchdown->z(), 0.0, 1e-9);
  EXPECT_GT((e.touchdown->head<2>() - Vec2(100, 100)).norm(), 0.4);  // beside, not under the goal
  const Trajectory& tr = e.plan.trajectory;
  EXPECT_EQ(tr.back().p, *e.touchdown);
  const std::vector<MissionItem> items = mission_items(sc, e, {});
  ASSERT_EQ(items.back().command, kCmdLand);
  const LatLonAlt td = GeoFrame(*sc.origin).to_wgs84(*e.touchdown);
  EXPECT_NEAR(items.back().params[4], td.lat_deg, 1e-8);
  EXPECT_NEAR(items.back().params[5], td.lon_deg, 1e-8);
}

TEST(Export, OnlyWhatHoldsLeavesTheTool) {
  const Scenario sc = scenario_with({Box{Vec3(40, -20, 0), Vec3(60, 20, 50)}});  // across the east leg
  VerifiedExport v = verified_export(sc, plan_of({sample_uav()}), {});
  EXPECT_FALSE(v.holds());
  ASSERT_EQ(v.left_out.size(), 1u);
  EXPECT_NE(v.left_out[0].find("a/1: does not hold: a/1 obstacle"), std::string::npos) << v.left_out[0];
  UavPlan failed = sample_uav();
  failed.status = Status::failed;
  failed.message = "no route";
  v = verified_export(scenario_with(), plan_of({failed}), {});
  ASSERT_EQ(v.left_out.size(), 1u);
  EXPECT_EQ(v.left_out[0], "a/1: failed (no route)");
  Plan ghost = plan_of({sample_uav()});
  ghost.uavs[0].id = "ghost";
  EXPECT_THROW(verified_export(scenario_with(), ghost, {}), ExportError);
}

TEST(Export, QgcPlanFollowsTheLoaderRules) {
  // A cylinder reaching above the flight height becomes an exclusion circle, a low box the UAV
  // flies over does not become a fence, a tall box becomes an exclusion polygon.
  const Scenario sc = scenario_with({Cylinder{Vec2(500, 500), 20, 0, 100}, Box{Vec3(200, 200, 0), Vec3(220, 220, 5)},
                                     Box{Vec3(300, 300, 0), Vec3(320, 320, 60)}});
  ExportOptions opt;
  opt.firmware = Firmware::ardupilot;
  const auto j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt));
  EXPECT_EQ(j["fileType"], "Plan");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["mission"]["version"], 2);
  EXPECT_EQ(j["mission"]["firmwareType"], 3);
  EXPECT_EQ(j["mission"]["plannedHomePosition"].size(), 3u);
  int do_items = 0;
  for (const auto& it : j["mission"]["items"]) {
    ASSERT_EQ(it["params"].size(), 7u);
    for (const auto& p : it["params"]) EXPECT_TRUE(p.is_number());
    if (it["frame"] == kFrameMission) {  // as QGroundControl writes DO commands: no altitude keys
      ++do_items;
      EXPECT_FALSE(it.contains("Altitude") || it.contains("AltitudeMode") || it.contains("AMSLAltAboveTerrain"));
      continue;
    }
    EXPECT_TRUE(it["AMSLAltAboveTerrain"].is_number());
    EXPECT_TRUE(it["Altitude"].is_number());
    EXPECT_TRUE(it["AltitudeMode"].is_number());
  }
  EXPECT_EQ(do_items, 2);  // the planned speed and its change
  EXPECT_EQ(j["geoFence"]["version"], 2);
  EXPECT_EQ(j["geoFence"]["circles"].size(), 1u);
  ASSERT_EQ(j["geoFence"]["polygons"].size(), 2u);  // bounds (inclusion) and the tall box
  EXPECT_EQ(j["geoFence"]["polygons"][0]["inclusion"], true);
  EXPECT_EQ(j["geoFence"]["polygons"][1]["inclusion"], false);
  EXPECT_EQ(j["rallyPoints"]["version"], 2);
}

TEST(Export, FenceKeepsTheLargestExclusionsAndSaysWhatItDropped) {
  std::vector<Obstacle> towers;
  towers.reserve(20);
  for (int k = 0; k < 20; ++k) towers.push_back(Box{Vec3(200 + 30 * k, 500, 0), Vec3(210 + 30 * k + k, 510 + k, 80)});
  const Scenario sc = scenario_with(towers);
  ExportOptions opt;
  std::vector<std::string> notes;
  auto j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt, &notes));
  ASSERT_EQ(j["geoFence"]["polygons"].size(), 17u);  // bounds and the 16 largest
  ASSERT_EQ(notes.size(), 2u);                       // and PX4's take-off height (Px4TakeoffHeightIsNamed)
  EXPECT_NE(notes[0].find("16 largest of 20"), std::string::npos) << notes[0];
  const GeoFrame f(*sc.origin);  // the smallest kept is tower 4 (footprint 14 x 14)
  EXPECT_NEAR(j["geoFence"]["polygons"][16]["polygon"][0][1].get<double>(), f.to_wgs84(Vec3(320, 500, 0)).lon_deg,
              1e-9);
  opt.fence = FenceMode::all;
  notes.clear();
  j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt, &notes));
  EXPECT_EQ(j["geoFence"]["polygons"].size(), 21u);
  ASSERT_EQ(notes.size(), 1u);  // nothing dropped: only the take-off's note
  EXPECT_NE(notes[0].find("NAV_ACC_RAD"), std::string::npos) << notes[0];
  opt.fence = FenceMode::none;
  j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt, &notes));
  EXPECT_TRUE(j["geoFence"]["polygons"].empty());
}

// Altitudes above sea level or the terrain (issue: real terrain, item 2): the same verified
// heights in each frame, terrain only for ArduPilot.
TEST(Export, AltitudeFramesCarryTheVerifiedHeights) {
  Scenario sc = scenario_with();
  WorldSpec w = sc.world.spec();
  w.terrain = TerrainGrid(Vec2(0, 0), 50.0, 20, 20, std::vector<double>(400, 0.0));
  sc.world = World(std::move(w));
  const GeoFrame f(*sc.origin);
  ExportOptions opt;
  const auto standard = mission_items(sc, exported(sc, opt), opt);
  EXPECT_EQ(standard[3].frame, kFrameGlobalRelativeAlt);  // no elevation model: above home
  sc.elevation = ElevationSource{};                       // an elevation model: above sea level
  const auto amsl = mission_items(sc, exported(sc, opt), opt);
  ASSERT_EQ(amsl.size(), standard.size());
  for (std::size_t k = 0; k < amsl.size(); ++k) {
    if (!amsl[k].positioned()) continue;
    EXPECT_EQ(amsl[k].frame, kFrameGlobal);
    EXPECT_NEAR(amsl[k].params[6], 488.0 + standard[k].params[6], 1e-3);  // home on the ground at z = 0
    EXPECT_DOUBLE_EQ(amsl[k].amsl_m, amsl[k].params[6]);
  }
  auto j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt));
  EXPECT_EQ(j["mission"]["items"][3]["AltitudeMode"], 2);
  EXPECT_EQ(j["mission"]["items"][3]["Altitude"], j["mission"]["items"][3]["AMSLAltAboveTerrain"]);

  opt.altitude = AltitudeFrame::terrain;
  EXPECT_THROW(mission_items(sc, exported(sc, opt), opt), ExportError);  // PX4 takes no frame 10
  opt.firmware = Firmware::ardupilot;
  WorldSpec hill = sc.world.spec();
  std::vector<double> h(400, 0.0);
  h[0 * 20 + 2] = 4.0;  // the cell under (100..150, 0..50): the first waypoint's ground is 4 m up
  hill.terrain = TerrainGrid(Vec2(0, 0), 50.0, 20, 20, h);
  sc.world = World(std::move(hill));
  const auto terrain = mission_items(sc, exported(sc, opt), opt);
  ASSERT_EQ(terrain[3].command, kCmdWaypoint);
  EXPECT_EQ(terrain[3].frame, kFrameGlobalTerrainAlt);
  EXPECT_NEAR(terrain[3].params[6], 10.0 - 4.0, 1e-9);  // z 10 over ground 4
  EXPECT_NEAR(terrain[3].amsl_m, 498.0, 1e-9);
  j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt));
  EXPECT_EQ(j["mission"]["items"][3]["AltitudeMode"], 4);
  EXPECT_NE(altitude_note(sc, opt)->find("ArduPilot follows its own terrain data"), std::string::npos);
}

// A fence read from a file is written back as it was read, corner for corner (issue: real
// airspace, item 3); the obstacles it became are not written again as exclusions.
TEST(Export, AFenceReadIsTheFenceWritten) {
  Scenario sc = scenario_with({Box{Vec3(400, 400, 0), Vec3(450, 450, 100)}});
  FenceZone inclusion;
  inclusion.inclusion = true;
  inclusion.polygon_latlon = {{47.39, 8.54}, {47.39, 8.56}, {47.41, 8.56}, {47.41, 8.54}};
  FenceZone circle;
  circle.center_latlon = {47.40012345678901, 8.55012345678901};
  circle.radius_m = 33.3;
  circle.obstacles = {0};  // the box stands for it here
  sc.airspace = {inclusion, circle};
  ExportOptions opt;
  const auto j = nlohmann::json::parse(qgc_plan_json(sc, exported(sc, opt), opt));
  const auto& fence = j["geoFence"];
  ASSERT_EQ(fence["polygons"].size(), 1u);  // the file's inclusion, not the bounds; the box not again
  EXPECT_TRUE(fence["polygons"][0]["inclusion"].get<bool>());
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(fence["polygons"][0]["polygon"][k][0].get<double>(), inclusion.polygon_latlon[k].x());
    EXPECT_EQ(fence["polygons"][0]["polygon"][k][1].get<double>(), inclusion.polygon_latlon[k].y());
  }
  ASSERT_EQ(fence["circles"].size(), 1u);
  EXPECT_FALSE(fence["circles"][0]["inclusion"].get<bool>());
  EXPECT_EQ(fence["circles"][0]["circle"]["center"][0].get<double>(), 47.40012345678901);
  EXPECT_EQ(fence["circles"][0]["circle"]["center"][1].get<double>(), 8.55012345678901);
  EXPECT_EQ(fence["circles"][0]["circle"]["radius"].get<double>(), 33.3);
}

TEST(Export, WplRowsMatchTheMission) {
  const Scenario sc = scenario_with();
  const ExportedUav e = exported(sc);
  const std::string text = qgc_wpl(sc, e, {});
  EXPECT_EQ(text.rfind("QGC WPL 110\n0\t1\t0\t16\t", 0), 0u);
  EXPECT_EQ(text.find('\r'), std::string::npos);
  std::size_t rows = 0;
  for (char c : text) rows += c == '\n';
  EXPECT_EQ(rows, 1u + 1u + mission_items(sc, e, {}).size());  // header, home, items
}

TEST(Export, GeoJsonIsLonLatAltWithIds) {
  Scenario sc = scenario_with(
      {Prism{{{0, 500}, {0, 510}, {10, 510}, {10, 500}}, 0, 5}, Box{Vec3(300, 300, 0), Vec3(320, 320, 60)}});
  WorldSpec ws = sc.world.spec();
  ws.obstacle_ids = {"", "tower"};
  sc.world = World(std::move(ws));
  const VerifiedExport v = verified_export(sc, plan_of({sample_uav()}), {});
  const auto j = nlohmann::json::parse(plan_geojson(sc, v));
  const auto& route = j["features"][0];
  EXPECT_EQ(route["geometry"]["type"], "LineString");
  // The take-off from the ground below the start, the hold collapsed, the straight legs' ends,
  // the landing.
  EXPECT_EQ(route["geometry"]["coordinates"].size(), 5u) << route.dump();
  EXPECT_NEAR(route["geometry"]["coordinates"][0][0].get<double>(), 8.5456, 1e-9);  // lon first
  EXPECT_NEAR(route["geometry"]["coordinates"][0][1].get<double>(), 47.3977, 1e-9);
  EXPECT_NEAR(route["geometry"]["coordinates"][0][2].get<double>(), 488.0, 1e-9);  // home on the ground
  EXPECT_NEAR(route["geometry"]["coordinates"][1][2].get<double>(), 498.0, 1e-9);  // the start
  EXPECT_EQ(j["features"][1]["properties"]["id"], "obstacle 0");
  EXPECT_EQ(j["features"][2]["properties"]["id"], "tower");
  const auto& ring = j["features"][1]["geometry"]["coordinates"][0];
  ASSERT_EQ(ring.size(), 5u);
  EXPECT_EQ(ring.front(), ring.back());
  double area2 = 0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i)
    area2 += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
             ring[i + 1][0].get<double>() * ring[i][1].get<double>();
  EXPECT_GT(area2, 0.0);  // counter-clockwise although given clockwise
  EXPECT_NE(plan_kml(sc, v).find("<name>tower (box"), std::string::npos);
}

TEST(Export, ClearErrorsAndCsvWithoutOrigin) {
  Scenario sc = scenario_with();
  sc.origin.reset();
  const VerifiedExport v = verified_export(sc, plan_of({sample_uav()}), {});
  EXPECT_THROW(export_files(sc, v, ExportFormat::qgc), ExportError);
  const auto csv = export_files(sc, v, ExportFormat::csv);
  ASSERT_EQ(csv.size(), 1u);
  // The take-off below the airborne start, at cruise speed before t = 0.
  EXPECT_EQ(csv[0].content.rfind("t,x,y,z\n-2,0,0,0\n0,0,0,10\n", 0), 0u) << csv[0].content;
}

TEST(Export, FileNamesAreSafeAndDistinct) {
  EXPECT_EQ(file_stem("a/1"), "a_1");
  EXPECT_EQ(file_stem("../x"), "_.._x");
  Scenario sc = scenario_with();
  UavSpec other = sc.uavs[0];
  other.id = "a?1";
  other.start = Vec3(0, 500, 10);
  sc.uavs.push_back(other);
  UavPlan second = sample_uav();
  second.id = "a?1";
  for (auto& s : second.trajectory) s.p.y() += 500;
  const auto files = export_files(sc, verified_export(sc, plan_of({sample_uav(), second}), {}), ExportFormat::csv);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_NE(files[0].name, files[1].name);
}

// A folder holds one export: the next removes what the last wrote and it does not write again,
// and only while the file still holds what was written; nothing a manifest was made to name.
TEST(Export, FolderManifestRemovesStaleFilesOnly) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       ("uavplan_manifest_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "mine.txt") << "user file";
  std::ofstream(dir / "plan.json") << "the plan";
  std::ofstream(dir / "sub" / "keep.plan") << "x";
  write_export(dir.string(), {{"q1.plan", "1", "q1"}, {"q5.plan", "5", "q5"}, {"q6.plan", "6", "q6"}});
  EXPECT_TRUE(fs::exists(dir / "q5.plan"));
  std::ofstream(dir / "q6.plan") << "edited by hand";
  // Hand-written lines: a path outside, plain names, and names with a made-up fingerprint.
  std::ofstream(dir / kExportManifest, std::ios::app)
      << "../sub/keep.plan\tcbf29ce484222325\nmine.txt\nplan.json\t0000000000000000\nmine.txt\tffffffffffffffff\n";
  write_export(dir.string(), {{"q1.plan", "1b", "q1"}});
  EXPECT_FALSE(fs::exists(dir / "q5.plan"));
  EXPECT_TRUE(fs::exists(dir / "q6.plan"));  // not what was written: somebody's now
  EXPECT_TRUE(fs::exists(dir / "q1.plan"));
  EXPECT_TRUE(fs::exists(dir / "sub" / "keep.plan"));
  EXPECT_TRUE(fs::exists(dir / "plan.json"));
  EXPECT_TRUE(fs::exists(dir / "mine.txt"));
  clear_export(dir.string());
  EXPECT_FALSE(fs::exists(dir / "q1.plan"));
  EXPECT_FALSE(fs::exists(dir / kExportManifest));
  EXPECT_TRUE(fs::exists(dir / "mine.txt"));
  EXPECT_TRUE(fs::exists(dir / "plan.json"));
  fs::remove_all(dir);
}

// File names are distinct by construction: ids that make the same safe name (or one another's
// numbered name, or differ only in case) get names no other UAV has; long ids stay short enough.
TEST(Export, FileStemsAreDistinctByConstruction) {
  Scenario sc = scenario_with();
  const std::vector<std::string> ids = {
      "a_b_2", "a_b", "a b", "A B", "a?b", std::string(300, 'x'), std::string(300, 'x') + "?"};
  std::vector<UavPlan> plans;
  sc.uavs.resize(1);
  const UavSpec first = sc.uavs[0];
  sc.uavs.clear();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    UavSpec u = first;
    u.id = ids[k];
    u.start.y() += 120.0 * static_cast<double>(k);
    if (u.goal) u.goal->y() += 120.0 * static_cast<double>(k);
    sc.uavs.push_back(u);
    UavPlan p = sample_uav();
    p.id = ids[k];
    for (auto& row : p.trajectory) row.p.y() += 120.0 * static_cast<double>(k);
    for (auto& w : p.waypoints) w.y() += 120.0 * static_cast<double>(k);
    plans.push_back(p);
  }
  const auto files = export_files(sc, verified_export(sc, plan_of(plans), {}), ExportFormat::csv);
  ASSERT_EQ(files.size(), ids.size());
  std::set<std::string> lower;
  for (std::size_t k = 0; k < files.size(); ++k) {
    std::string l = files[k].name;
    for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_TRUE(lower.insert(l).second) << files[k].name << " twice";
    EXPECT_LT(files[k].name.size(), 120u);
    EXPECT_EQ(files[k].uav, ids[k]);
  }
  EXPECT_EQ(files[0].name, "a_b_2.csv");
  EXPECT_EQ(files[1].name, "a_b.csv");
}

}  // namespace
}  // namespace uavplan

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/io/files.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan {
namespace {

// P5's reference UAV flown through the autopilot model: a row every second along its arcs.
struct ModelFlown {
  Scenario sc;
  Plan plan;
  ModelFlown() {
    const std::string path = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/p5_entry.yaml";
    sc = parse_scenario(read_text_file(path) + "origin: {lat: 30.5, lon: 104.0, alt: 500}\n", path);
    plan = plan_mission(sc, {});
    finalize_plan(sc, plan);
  }
};

std::size_t waypoints(const std::vector<MissionItem>& items) {
  return static_cast<std::size_t>(
      std::count_if(items.begin(), items.end(), [](const MissionItem& i) { return i.command == kCmdWaypoint; }));
}

TEST(ExportSimplify, AModelFlownTrajectoryIsFlownAsVerifiedChords) {
  const ModelFlown m;
  ASSERT_EQ(m.plan.status, Status::solved) << m.plan.message;
  ExportOptions all_rows;
  all_rows.simplify_m = 0.0;
  const VerifiedExport full = verified_export(m.sc, m.plan, all_rows);
  const VerifiedExport chords = verified_export(m.sc, m.plan, {});
  ASSERT_TRUE(full.holds() && chords.holds());
  const Trajectory& a = full.uavs[0].plan.trajectory;
  const Trajectory& b = chords.uavs[0].plan.trajectory;
  const std::size_t n_full = waypoints(mission_items(m.sc, full.uavs[0], all_rows));
  const std::size_t n_chords = waypoints(mission_items(m.sc, chords.uavs[0], {}));
  EXPECT_LT(3 * n_chords, n_full) << n_chords << " of " << n_full;
  EXPECT_LT(3 * b.size(), a.size());
  // Every row flown is a row of the plan, and every row left out is within the UAV's radius of
  // where the chord has it at that time.
  const double tol = m.sc.uavs[0].radius_m;
  std::size_t k = 0;
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    while (k < a.size() && a[k].t_s < b[i].t_s) ++k;
    ASSERT_LT(k, a.size());
    ASSERT_EQ(a[k].p, b[i].p);
    for (std::size_t r = k + 1; r < a.size() && a[r].t_s < b[i + 1].t_s; ++r) {
      const double f = (a[r].t_s - b[i].t_s) / (b[i + 1].t_s - b[i].t_s);
      EXPECT_LE((a[r].p - (b[i].p + f * (b[i + 1].p - b[i].p))).norm(), tol + 1e-9);
    }
  }
  EXPECT_EQ(b.back().p, a.back().p);
}

// Chords that do not hold are not flown: the tolerance is halved until they do.
TEST(ExportSimplify, ChordsThatDoNotHoldAreHalvedUntilTheyDo) {
  const ModelFlown m;
  ExportOptions coarse;
  coarse.simplify_m = 1e6;  // one chord from start to goal: through the no-fly cylinder
  ExportOptions all_rows;
  all_rows.simplify_m = 0.0;
  const VerifiedExport e = verified_export(m.sc, m.plan, coarse);
  ASSERT_TRUE(e.holds());
  const std::size_t rows = e.uavs[0].plan.trajectory.size();
  EXPECT_GT(rows, 2u);  // not the one chord through the cylinder
  EXPECT_LT(rows, verified_export(m.sc, m.plan, all_rows).uavs[0].plan.trajectory.size());
}

// PX4 up to v1.14 refuses a take-off below NAV_ACC_RAD + 1 m above home (11 m by default): a
// take-off to 10 m is named with what to set; one to 12 m, or for ArduPilot, is not.
TEST(Export, Px4TakeoffHeightIsNamed) {
  const Scenario sc = scenario_with();
  std::vector<std::string> notes;
  qgc_plan_json(sc, exported(sc), {}, &notes);  // the sample starts 10 m up
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("climbs 10 m above home"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("NAV_ACC_RAD to 9 m or less"), std::string::npos) << notes[0];
  Scenario higher = sc;
  higher.uavs[0].start.z() = 12.0;
  UavPlan high = sample_uav();
  for (auto& row : high.trajectory) row.p.z() = 12.0;
  notes.clear();
  qgc_plan_json(higher, exported(higher, {}, high), {}, &notes);
  EXPECT_TRUE(notes.empty());
  ExportOptions ardupilot;
  ardupilot.firmware = Firmware::ardupilot;
  qgc_plan_json(sc, exported(sc, ardupilot), ardupilot, &notes);
  EXPECT_TRUE(notes.empty());
}

// PX4 up to v1.14 refuses a first waypoint more than MIS_DIST_1WP (900 m) from home and legs
// longer than MIS_DIST_WPS (900 m): the export says so, naming the parameter; ArduPilot has no
// such rule.
TEST(Export, Px4DistanceRulesAreNamed) {
  Scenario sc = scenario_with();
  sc.origin->alt_m = 1500.0;  // distances are horizontal: the altitude does not count
  UavPlan u = sample_uav();
  u.trajectory = {{0.0, Vec3(0, 0, 10)}, {100.0, Vec3(500, 0, 10)}, {300.0, Vec3(500, 950, 10)}};
  std::vector<std::string> notes;
  // The distance notes (a take-off to 10 m adds PX4's take-off note: Px4TakeoffHeightIsNamed).
  const auto distance_notes = [&] {
    std::vector<std::string> d;
    for (const std::string& n : notes)
      if (n.find("MIS_DIST") != std::string::npos) d.push_back(n);
    return d;
  };
  qgc_plan_json(sc, exported(sc, {}, u), {}, &notes);
  ASSERT_EQ(distance_notes().size(), 1u);
  EXPECT_NE(distance_notes()[0].find("MIS_DIST_WPS"), std::string::npos) << distance_notes()[0];
  EXPECT_NE(distance_notes()[0].find("950 m"), std::string::npos) << distance_notes()[0];
  u.trajectory = {{0.0, Vec3(0, 0, 10)}, {190.0, Vec3(950, 0, 10)}, {200.0, Vec3(950, 50, 10)}};
  notes.clear();
  qgc_plan_json(sc, exported(sc, {}, u), {}, &notes);
  ASSERT_EQ(distance_notes().size(), 1u);  // its legs are short
  EXPECT_NE(distance_notes()[0].find("MIS_DIST_1WP"), std::string::npos) << distance_notes()[0];
  ExportOptions ardupilot;
  ardupilot.firmware = Firmware::ardupilot;
  notes.clear();
  qgc_plan_json(sc, exported(sc, ardupilot, u), ardupilot, &notes);
  EXPECT_TRUE(notes.empty());
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

// A UAV flying a half circle 1 m off a mast's radius, in 1,500 rows (a direction change each).
struct CloseArc {
  Scenario sc = test::scenario_with({Cylinder{Vec2(500, 500), 20.0, 0.0, 100.0}});
  Plan plan;
  CloseArc() {
    sc.uavs[0].start = Vec3(479, 500, 10);
    UavPlan u = test::sample_uav();
    u.trajectory.clear();
    constexpr int kRows = 1500;
    const double step_s = kPi * 21.0 / 5.0 / (kRows - 1);  // 5 m/s along the arc
    for (int k = 0; k < kRows; ++k) {
      const double a = kPi - kPi * k / (kRows - 1);
      u.trajectory.push_back({k * step_s, Vec3(500 + 21 * std::cos(a), 500 + 21 * std::sin(a), 10)});
    }
    plan = test::plan_of({u});
  }
};

// No mission exceeds what its firmware stores: a longer one is flown as fewer chords that hold
// (here within a centimetre or two of the arc); where no chords that few hold, the UAV is left
// out, naming the limit.
TEST(ExportItems, AMissionOverTheFirmwaresStoreIsFlownAsFewerChords) {
  const CloseArc arc;
  for (const Firmware fw : {Firmware::ardupilot, Firmware::px4}) {
    ExportOptions opt;
    opt.firmware = fw;
    // By default an autopilot flies chords within the body's radius: a few items.
    const VerifiedExport chords = verified_export(arc.sc, arc.plan, opt);
    ASSERT_TRUE(chords.holds()) << chords.left_out.front();
    EXPECT_LT(mission_items(arc.sc, chords.uavs[0], opt).size(), 20u);
    opt.simplify_m = 0.0;  // every row asked for: more than the store, so fewer chords
    const VerifiedExport v = verified_export(arc.sc, arc.plan, opt);
    ASSERT_TRUE(v.holds()) << v.left_out.front();
    const std::size_t items = mission_items(arc.sc, v.uavs[0], opt).size();
    EXPECT_LE(items, static_cast<std::size_t>(mission_item_limit(opt)));
    EXPECT_GT(items, 20u);  // the arc is still flown as an arc
    ExportOptions all;
    all.firmware = fw;
    all.max_items = 65535;
    all.simplify_m = 0.0;
    EXPECT_GT(mission_items(arc.sc, verified_export(arc.sc, arc.plan, all).uavs[0], all).size(), 1500u);
  }
  ExportOptions few;
  few.max_items = 8;
  const VerifiedExport v = verified_export(arc.sc, arc.plan, few);
  ASSERT_FALSE(v.holds());
  EXPECT_NE(v.left_out.front().find("more than the 8 the PX4 firmware stores"), std::string::npos)
      << v.left_out.front();
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

// An airborne start 10 m above home: ArduCopter arms, lifts off after 4.2 s, climbs at 2.5 m/s
// (0.4 s more to reach that speed and stop), rests 1.3 s and then falls 0.625 s behind a start
// at 5 m/s on its ramp (1.25 s: 20 m/s^3 to 5 m/s^2, held, and back), so its mission starts
// 10.5 s before the plan's t = 0; PX4 keeps the export's timing (the climb at cruise speed,
// 5 m/s). schedule.json lists each UAV's start and its files.
TEST(ExportSchedule, MissionsStartSoThatTheTakeOffEndsAtThePlansStart) {
  const Scenario sc = test::scenario_with();
  const Plan plan = test::plan_of({test::sample_uav()});
  ExportOptions ardupilot;
  ardupilot.firmware = Firmware::ardupilot;
  const std::vector<ScheduledStart> copter = flight_schedule(sc, verified_export(sc, plan, ardupilot), ardupilot);
  ASSERT_EQ(copter.size(), 1u);
  EXPECT_NEAR(copter[0].start_s, -(4.2 + 10.0 / 2.5 + 0.4 + 1.3 + 0.625), 1e-9);
  EXPECT_NEAR(copter_ramp_lag_s(5.0), 0.5 * (5.0 / 5.0 + 5.0 / 20.0), 1e-12);  // at 5 m/s^2 from 1.25 m/s
  EXPECT_NEAR(copter_ramp_lag_s(1.0), std::sqrt(1.0 / 20.0), 1e-12);           // jerk-limited throughout
  // Its landing after 34 s: 10 m, all below LAND_ALT_LOW, at LAND_SPEED 0.5 m/s as NAV_LAND
  // descends; PX4's at cruise speed (5 m/s).
  EXPECT_NEAR(copter[0].flight_s, 34.0 + 10.0 / 0.5 - copter[0].start_s, 1e-9);
  const std::vector<ScheduledStart> px4 = flight_schedule(sc, verified_export(sc, plan, {}), {});
  EXPECT_NEAR(px4[0].start_s, -10.0 / 5.0, 1e-9);
  EXPECT_NEAR(px4[0].flight_s, 34.0 + 10.0 / 5.0 - px4[0].start_s, 1e-9);
  const nlohmann::json j = nlohmann::json::parse(schedule_json(copter, {{"a/1", "a_1.plan"}, {"b", "b.plan"}}));
  EXPECT_EQ(j["uavs"][0]["id"], "a/1");
  EXPECT_EQ(j["uavs"][0]["files"], nlohmann::json::array({"a_1.plan"}));
  EXPECT_DOUBLE_EQ(j["uavs"][0]["start_s"].get<double>(), copter[0].start_s);
}

// ISA: the equivalent airspeed of 1 m/s true, sqrt(rho / rho0): 1 at sea level, 0.7754 at
// 5,000 m (rho 0.7361 kg/m^3 of 1.225), 0.5451 at the tropopause (0.3639), held above it.
TEST(ExportSchedule, EquivalentAirspeedFollowsTheStandardAtmosphere) {
  EXPECT_NEAR(equivalent_per_true_airspeed(0.0), 1.0, 1e-12);
  EXPECT_NEAR(equivalent_per_true_airspeed(5000.0), std::sqrt(0.7361 / 1.225), 5e-4);
  EXPECT_NEAR(equivalent_per_true_airspeed(11000.0), std::sqrt(0.3639 / 1.225), 5e-4);
  EXPECT_DOUBLE_EQ(equivalent_per_true_airspeed(15000.0), equivalent_per_true_airspeed(11000.0));
}

// A fixed wing's DO_CHANGE_SPEED is the equivalent airspeed of the leg's planned speed at the
// altitude it starts from: about 5 m/s true at 510 m above sea level (the origin's 500 + 10).
TEST(ExportSchedule, AFixedWingIsCommandedItsEquivalentAirspeed) {
  Scenario sc = test::scenario_with();
  sc.world = World(WorldSpec{Aabb{Vec3(-1000, -1000, 0), Vec3(1000, 1000, 100)}, {}, {}, {}, {}, {}, {}});
  sc.origin->alt_m = 500.0;
  ExportOptions opt;
  opt.firmware = Firmware::ardupilot;
  opt.vehicle = VehicleKind::fixed_wing;
  const std::vector<MissionItem> items = mission_items(sc, exported(sc, opt), opt);
  std::size_t k = 1;  // the first: the plan's first leg, at 5 m/s
  while (k < items.size() && items[k].command != kCmdChangeSpeed) ++k;
  ASSERT_LT(k, items.size());
  EXPECT_EQ(items[k].params[0], 0.0);  // airspeed
  EXPECT_NEAR(items[k].params[1] / equivalent_per_true_airspeed(items[k - 1].amsl_m), 5.0, 0.25);
  EXPECT_LT(items[k].params[1], 5.0 * 0.99);
}

}  // namespace
}  // namespace uavplan
