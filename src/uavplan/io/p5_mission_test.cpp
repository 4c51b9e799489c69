// The P5 formation mission end to end (scenarios/p5_mission.yaml): every phase done in order, the
// plan verified (cylinders, separation in the air, task points at their headings, every UAV
// stopped on the runway), the same bytes for the same seed; and its bad input.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "uavplan/coordination/contract/runway.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation_mission/task_points.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/io/flight_export.h"
#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/mission_items.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan {
namespace {

const std::string kScenario = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/p5_mission.yaml";

TEST(P5Mission, AllFivePhasesFlownAndVerified) {
  const Scenario sc = load_scenario(kScenario);
  MissionOptions o;
  Plan plan = plan_mission(sc, o);
  EXPECT_TRUE(finalize_plan(sc, plan).empty());
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  ASSERT_TRUE(plan.formation);
  const std::vector<std::string> names{"form_up", "mission", "return", "dismiss", "landing"};
  ASSERT_EQ(plan.formation->phases.size(), names.size());
  double last = 0.0;
  for (std::size_t k = 0; k < names.size(); ++k) {
    EXPECT_EQ(plan.formation->phases[k].name, names[k]);
    EXPECT_GT(plan.formation->phases[k].end_s, last) << names[k];
    last = plan.formation->phases[k].end_s;
  }
  EXPECT_GE(plan.metrics.at("min_separation_m"), 50.0);
  for (const UavPlan& u : plan.uavs) EXPECT_NEAR(u.trajectory.back().p.z(), 0.0, 1e-9) << u.id;  // landed
  Plan again = plan_mission(sc, o);
  finalize_plan(sc, again);
  EXPECT_EQ(plan_to_json(plan), plan_to_json(again));
}

// The same mission with the world cut short behind the threshold (runway heading east): P5's
// landing cylinder (3 km wide, 10 km before it) would leave the bounds, so it and the gate come
// in; the plan flies inside the bounds and lands. Cut shorter, where P5's vehicles (70 m/s at
// 2.2 deg/s: a 1.8 km turn) could not circle in what fits, the mission fails saying why.
TEST(P5Mission, TheLandingApproachFitsAWorldCutShortBehindTheRunway) {
  const Scenario full = load_scenario(kScenario);
  const auto cut_at = [&](double behind_m) {
    Scenario sc = full;
    WorldSpec ws = sc.world.spec();
    ws.bounds.min.x() = sc.mission.airfield->position.x() - behind_m;
    sc.world = World(std::move(ws));
    return sc;
  };
  const Scenario roomy = cut_at(12000.0);
  Plan plan = plan_mission(roomy, MissionOptions{});
  EXPECT_TRUE(finalize_plan(roomy, plan).empty());
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  EXPECT_TRUE(verify_plan(roomy, plan).empty());
  double westmost = 1e300;
  for (const UavPlan& u : plan.uavs)
    for (const auto& row : u.trajectory) westmost = std::min(westmost, row.p.x());
  EXPECT_LT(westmost, full.mission.airfield->position.x() - 6000.0);  // the approach from the west
  const Scenario tight = cut_at(8000.0);
  Plan failed = plan_mission(tight, MissionOptions{});
  finalize_plan(tight, failed);
  EXPECT_EQ(failed.status, Status::failed);
  EXPECT_NE(failed.uavs.front().message.find("no room for the landing approach"), std::string::npos)
      << failed.uavs.front().message;
}

// P5's mission flown by aircraft of ArduPlane's class (scenarios/p5_small.yaml: 20 m/s turning
// at 6 deg/s in a 6 km world, 20 m apart): the departure, the landing cylinder and the form-up
// layers at their scale, not P5's (15 km out, 1000 m up: outside this world), every phase done
// and the plan verified; the landing circles at the least speed where the faster ones do not fit.
TEST(P5Mission, SmallAircraftFlyTheMissionAtTheirScale) {
  const Scenario sc = load_scenario(std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/p5_small.yaml");
  Plan plan = plan_mission(sc, MissionOptions{});
  EXPECT_TRUE(finalize_plan(sc, plan).empty());
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  EXPECT_TRUE(verify_plan(sc, plan).empty());
  ASSERT_TRUE(plan.formation);
  ASSERT_EQ(plan.formation->phases.size(), 5u);
  EXPECT_GE(plan.metrics.at("min_separation_m"), sc.mission.separation_m);
  for (const UavPlan& u : plan.uavs) {
    double top = 0.0;
    for (const auto& row : u.trajectory) top = std::max(top, row.p.z());
    EXPECT_LT(top, 400.0) << u.id;  // layers 40 m apart from 150 m up, the task points at 120 m
    EXPECT_NEAR(u.trajectory.back().p.z(), 0.0, 1e-9) << u.id;
  }
}

// Exported for ArduPlane, the schedule names each aircraft a fixed wing (fly starts ArduPlane for
// it) and lists the parameters its flight needs: its airspeed range and cruise as equivalent
// airspeeds (ArduPlane ignores a DO_CHANGE_SPEED outside AIRSPEED_MIN..AIRSPEED_MAX) and RTL_AUTOLAND (without it ArduPlane
// refuses to arm a mission holding DO_LAND_START).
TEST(P5Mission, TheArduPlaneScheduleListsTheParametersItsLandingAndSpeedsNeed) {
  const Scenario sc = load_scenario(std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/p5_small.yaml");
  const Plan plan = plan_mission(sc, MissionOptions{});
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  ExportOptions opt;
  opt.firmware = Firmware::ardupilot;
  opt.vehicle = VehicleKind::fixed_wing;
  const std::vector<ScheduledStart> schedule = flight_schedule(sc, verified_export(sc, plan, opt), opt);
  ASSERT_EQ(schedule.size(), sc.uavs.size());
  const nlohmann::json j = nlohmann::json::parse(schedule_json(schedule, {}));
  // Equivalent airspeeds (ISA): 14 m/s true at the highest row, 28 at the airfield, 584 m up.
  double top_m = 0.0;
  for (const UavPlan& u : plan.uavs)
    for (const auto& row : u.trajectory) top_m = std::max(top_m, row.p.z());
  const double home_amsl = sc.origin->alt_m;
  for (const nlohmann::json& u : j["uavs"]) {
    EXPECT_EQ(u["vehicle"], "fixed_wing");
    const nlohmann::json& p = u["parameters"];
    EXPECT_LE(p["AIRSPEED_MIN"].get<double>(), 14.0 * equivalent_per_true_airspeed(home_amsl + top_m));
    EXPECT_GT(p["AIRSPEED_MIN"].get<double>(), 14.0 * equivalent_per_true_airspeed(home_amsl + top_m) - 1.0);
    EXPECT_NEAR(p["AIRSPEED_CRUISE"].get<double>(), 20.0 * equivalent_per_true_airspeed(home_amsl), 0.005);
    EXPECT_GE(p["AIRSPEED_MAX"].get<double>(), 28.0 * equivalent_per_true_airspeed(home_amsl));
    EXPECT_EQ(p["RTL_AUTOLAND"], 2.0);
  }
  for (std::size_t k = 1; k < schedule.size(); ++k) EXPECT_GT(schedule[k].start_s, schedule[k - 1].start_s);
}

// The verified plan exports whole, as fixed wing (landed UAVs are gone, not parked on one
// another at the runway's stop point): the take-off from the threshold along the runway, the
// flight as planned, PX4's landing pattern onto the planned touch-down within FW_LND_ANG; a
// multirotor export is refused with what to do.
TEST(P5Mission, EveryUavExportsAsFixedWing) {
  const Scenario sc = load_scenario(kScenario);
  const Plan plan = plan_mission(sc, MissionOptions{});
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  ExportOptions opt;
  opt.vehicle = VehicleKind::fixed_wing;
  const VerifiedExport e = verified_export(sc, plan, opt);
  EXPECT_EQ(e.uavs.size(), sc.uavs.size());
  for (const std::string& why : e.left_out) ADD_FAILURE() << why;
  const Airfield& af = *sc.mission.airfield;
  for (const ExportedUav& x : e.uavs) {
    EXPECT_LT((x.home - af.position).norm(), 1e-6) << x.spec->id;  // lined up at the threshold
    EXPECT_GT(x.takeoff_to.z(), af.position.z() + kAirborneAbove_m) << x.spec->id;
    EXPECT_NEAR(x.takeoff_to.y(), af.position.y(), 1e-6) << x.spec->id;  // straight out along the runway
    ASSERT_TRUE(x.approach && x.touchdown) << x.spec->id;
    EXPECT_NEAR(x.touchdown->z(), af.position.z(), 1e-9);
    const Vec3 glide = *x.approach - *x.touchdown;
    EXPECT_LE(std::atan2(glide.z(), glide.head<2>().norm()), deg_to_rad(kFixedWingGlide_deg)) << x.spec->id;
    EXPECT_GT(x.departure_s, 0.0);
    const std::vector<MissionItem> items = mission_items(sc, x, opt);
    EXPECT_EQ(items.front().command, kCmdTakeoff);
    EXPECT_GT(items.front().params[0], 0.0);  // the climb pitch
    ASSERT_GE(items.size(), 3u);
    EXPECT_EQ(items[items.size() - 3].command, kCmdLandStart);
    EXPECT_EQ(items[items.size() - 2].command, kCmdWaypoint);
    EXPECT_EQ(items.back().command, kCmdLand);
  }
  const VerifiedExport mr = verified_export(sc, plan, ExportOptions{});
  EXPECT_TRUE(mr.uavs.empty());
  ASSERT_FALSE(mr.left_out.empty());
  EXPECT_NE(mr.left_out[0].find("--vehicle fixedwing"), std::string::npos) << mr.left_out[0];
}

// What the verifier must catch in a formation_mission plan: a UAV that does not land on the
// runway, and a formation that misses a task point's entry heading.
TEST(P5Mission, TheVerifierCatchesAMissedRunwayAndATaskPointMissed) {
  Scenario sc = load_scenario(kScenario);
  const Plan plan = plan_mission(sc, MissionOptions{});
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  Plan off = plan;
  off.uavs[0].trajectory.back().p.y() += 500.0;
  bool runway = false;
  for (const Violation& v : verify_plan(sc, off)) runway = runway || (v.kind == ViolationKind::goal && v.uav == "u1");
  EXPECT_TRUE(runway);
  auto& points = sc.mission.edit_section<PhasedFormationSection>().task_points;
  points[1].entry_heading_rad = *points[1].entry_heading_rad + kPi / 2;
  bool task = false;
  for (const Violation& v : verify_plan(sc, plan)) task = task || v.kind == ViolationKind::via_point;
  EXPECT_TRUE(task);
}

// The runway holds one UAV at a time, from lining up to climbing out and from touchdown to the
// end of the roll-out; the verifier fails a plan where a UAV lands while another rolls out.
TEST(P5Mission, TheRunwayHoldsOneUavAtATime) {
  const Scenario sc = load_scenario(kScenario);
  const Plan plan = plan_mission(sc, MissionOptions{});
  ASSERT_EQ(plan.status, Status::solved) << plan.message;
  const Airfield& af = *sc.mission.airfield;
  std::vector<std::vector<TimeSpan>> occ;
  for (const UavPlan& u : plan.uavs) {
    occ.push_back(runway_occupancy(af, u.trajectory));
    EXPECT_EQ(occ.back().size(), 2u) << u.id;  // the take-off and the landing
  }
  for (std::size_t i = 0; i < occ.size(); ++i)
    for (std::size_t j = i + 1; j < occ.size(); ++j)
      EXPECT_FALSE(runway_overlap(occ[i], occ[j])) << plan.uavs[i].id << " " << plan.uavs[j].id;
  // The first to land held back in the air (time only, no row moved) until it touches down 5 s
  // after another's touchdown.
  std::size_t first = 0, other = 1;
  if (occ[other].back().from_s < occ[first].back().from_s) std::swap(first, other);
  Plan late = plan;
  const double shift = occ[other].back().from_s + 5.0 - occ[first].back().from_s;
  ASSERT_GT(shift, 0.0);
  for (TrajectorySample& row : late.uavs[first].trajectory)
    if (row.t_s > occ[first].front().to_s + 60.0) row.t_s += shift;
  bool runway = false;
  for (const Violation& v : verify_plan(sc, late)) runway = runway || v.kind == ViolationKind::runway;
  EXPECT_TRUE(runway);
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

void expect_bad(const std::string& text, const std::string& part) {
  try {
    parse_scenario(text, "m.yaml");
    FAIL() << "no error for " << part;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' not in: " << msg;
  }
}

TEST(P5Mission, BadInputIsOneLineNamingThePlace) {
  const std::string good = text_of(kScenario);
  expect_bad(
      replaced(good, "  airfield: {position: [50000, 50000, 0], runway_heading_deg: 0, runway_length: 3000}\n", ""),
      "airfield");
  expect_bad(replaced(good, "[409000, 271000, 5000]", "[173000, 455000, 5000]"), "inside obstacle nofly1");
  expect_bad(replaced(good, "[409000, 271000, 5000]", "[409000, 271000, 50000]"), "outside the world bounds");
  expect_bad(replaced(good, "start: [50200, 49800, 0]", "start: [50030, 49800, 0]"), "at least the separation");
  expect_bad(replaced(good, "start: [50400, 49800, 0]", "start: [51400, 50020, 0]"), "parked on the runway");
  expect_bad(replaced(good, "[-120, 0, 0]]", "[-120, 0, 0], [-180, 0, 0]]"), "slots for 4 UAVs");
  expect_bad(replaced(good, "  task_points:",
                      "  topology: [[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, 0, 1], [0, 0, 1, 0]]\n  task_points:"),
             "connected");
  expect_bad(replaced(good, "start: [50000, 49800, 0]", "start: [50000, 49800, 0], goal: [60000, 60000, 5000]"),
             "no goal");
}

}  // namespace
}  // namespace uavplan
