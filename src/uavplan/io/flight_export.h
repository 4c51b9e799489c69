// What leaves the tool: the UAVs of a plan that hold under the verifier, each with the legs its
// mission file adds to the plan, and those legs verified like the rest.
//  - The take-off: a plan that starts on the ground has its vertical take-off in the trajectory;
//    an airborne start implies one from the ground below it (multirotor: vertical; fixed wing:
//    a straight climb-out at min(max_climb, 10 deg) along the start heading ending at the start).
//    It happens before t = 0, so it is checked against obstacles, terrain and the bounds, not in
//    time.
//  - The end (--end): `land` descends vertically from the goal (multirotor; a plan that lands
//    at its goal already has it) or glides at 4.9 degrees (within FW_LND_ANG 5 by PX4's measure)
//    straight on, or turned by at most the turn limit, to a touch-down point (fixed wing: DO_LAND_START, approach, NAV_LAND); `rtl`
//    turns back within the turn limit, flies straight to above home at the goal's height and
//    comes down (multirotor) or circles there (fixed wing); `loiter` holds at the goal
//    (multirotor) or circles it at the autopilot's loiter radius (fixed wing: 80 m PX4, 60 m
//    ArduPilot); `none` adds nothing. End legs are flown at cruise speed from the arrival (an
//    ArduCopter mission's vertical landing as NAV_LAND descends: LAND_SPEED_HIGH, then LAND_SPEED
//    below LAND_ALT_LOW) and verified with every other exported UAV's trajectory (separation,
//    obstacles, terrain, moving obstacles, bounds, limits).
// A UAV is left out, with the reason, when it is not solved, has a violation, or an added leg
// does not hold. A fixed-wing UAV cannot fly a vertical take-off or landing: such plans are left
// out with what to change.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {

enum class Firmware { px4, ardupilot };             // QGC firmwareType 12 / 3
enum class VehicleKind { multirotor, fixed_wing };  // MAV_TYPE 2 / 1
enum class MissionEnd { land, rtl, loiter, none };
enum class FenceMode { none, bounds, all };  // bounds: plus the largest exclusions
// Mission altitudes: above home (MAV_FRAME_GLOBAL_RELATIVE_ALT), above mean sea level
// (MAV_FRAME_GLOBAL) or above the terrain (MAV_FRAME_GLOBAL_TERRAIN_ALT, ArduPilot only); `standard`:
// above sea level where the scenario's terrain is an elevation model, else above home.
enum class AltitudeFrame { standard, home, amsl, terrain };
std::string_view to_string(MissionEnd e);

// Thrown when a plan cannot be exported (no origin, a plan UAV unknown to the scenario).
class ExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExportOptions {
  Firmware firmware = Firmware::px4;
  VehicleKind vehicle = VehicleKind::multirotor;
  MissionEnd end = MissionEnd::land;
  // Legs whose speeds differ by less than this fraction of the current mission speed fly at it
  // (no DO_CHANGE_SPEED item): a group plan's speeds wobble by a few percent leg to leg. A leg
  // merged so keeps the speed while the time gained or lost on the plan, summed over the legs
  // flown at it, stays within speed_drift_s; a new speed pays that time back (within the
  // fraction of the leg's own speed).
  double speed_change_fraction = 0.10;
  double speed_drift_s = 0.5;
  FenceMode fence = FenceMode::bounds;
  AltitudeFrame altitude = AltitudeFrame::standard;
  int max_fence_exclusions = 16;  // FenceMode::bounds: autopilots store few fence points
  // A trajectory is flown as a subset of its rows: each left-out row within this distance of
  // where the UAV is at that time on the chord between the rows kept (synchronised distance, so
  // timing holds too). Negative: for autopilot missions the larger of the UAV's radius and what
  // it flies at cruise speed in 0.3 s (an autopilot rounds its turns by about as much, and slows
  // at every waypoint: a planner's rows a metre apart are flown at a crawl), the radius for
  // model-flown UAVs (rows every fraction of a second along arcs), none for the others. The
  // chords are verified with everything else that flies; where they do not hold the tolerances
  // are halved (down to 1 cm), then every UAV flies all its rows.
  double simplify_m = -1.0;
  // A flat (2-D) world's plan is flown this high above its home (multirotors): its obstacles are
  // columns at every height, so the distances verified in the plane hold up there; the take-off
  // climbs to it and the landing (or the return home) comes down from it.
  double flat_altitude_m = 20.0;
  // The most mission items one UAV's mission may hold; 0: what the firmware stores
  // (mission_item_limit). A mission over it is flown as fewer chords of its rows (as simplify_m,
  // the tolerance doubled until it fits and the chords hold with everything else that flies).
  int max_items = 0;
  // Whether a mission file for an autopilot is written (qgc, wpl). Without one (csv, geojson,
  // kml) a UAV whose take-off or end legs cannot be flown is still written, as planned, without
  // them (VerifiedExport::notes says so).
  bool autopilot = true;
};

inline constexpr double kFixedWingGlide_deg = 5.0;  // PX4 FW_LND_ANG default: the steepest glide
// The glide flown: 0.1 deg under it, so that PX4's own distance (on a sphere) still measures the
// glide within FW_LND_ANG (5.011 deg at exactly 5 in the plan's frame).
inline constexpr double kFixedWingGlideFlown_deg = 4.9;
inline constexpr double kFixedWingClimbOut_deg = 10.0;  // PX4 FW_TKO_PITCH_MIN default
double fixed_wing_loiter_radius_m(Firmware f);          // NAV_LOITER_RAD 80 m / WP_LOITER_RAD 60 m
// The mission items a UAV's mission may hold: options.max_items, else what the firmware stores:
// ArduPilot 650 (its SITL's store: "Only 650 items are supported"; boards with 16 KB of storage
// hold about as many), PX4 500 (NUM_MISSIONS_SUPPORTED on its NuttX boards).
int mission_item_limit(const ExportOptions& options);

struct ExportedUav {
  const UavSpec* spec = nullptr;
  UavPlan plan;                    // the trajectory it flies: the plan's, and its end legs
  std::size_t body_begin = 0;      // first row after a vertical take-off in the plan (0: none)
  std::size_t body_end = 0;        // last row before the end legs (and before a landing in the plan)
  Vec3 home = Vec3::Zero();        // on the ground: where it takes off
  Vec3 takeoff_to = Vec3::Zero();  // the top of its take-off
  MissionEnd end = MissionEnd::none;
  std::optional<Vec3> approach;     // fixed-wing landing: where the glide begins
  std::optional<Vec3> touchdown;    // land: where it touches down
  std::vector<Vec3> return_points;  // rtl: the turn back and the point above home
  double loiter_radius_m = 0.0;     // loiter (and fixed-wing rtl at home)
  // When its mission starts (the climb from the ground, a runway roll): a plan that waits on the
  // ground first (its departure) is flown from this time of the plan.
  double departure_s = 0.0;
  bool takeoff_before = false;  // an airborne start: its take-off is flown before t = 0
};

// The rows the files show: the plan's, after the take-off of an airborne start, timed at cruise
// speed before t = 0 (home, the top of the take-off, the start).
Trajectory exported_rows(const ExportedUav& uav);

struct VerifiedExport {
  std::vector<ExportedUav> uavs;      // what may be written, in plan order
  std::vector<std::string> left_out;  // "ID: why" (and "the plan: why" for mission-level ones)
  std::vector<Violation> violations;  // the verifier's findings behind them
  std::vector<std::string> notes;     // "ID: ..." UAVs written as planned, without added legs
  bool holds() const { return left_out.empty(); }
};

// Throws ExportError for a plan UAV the scenario lacks.
VerifiedExport verified_export(const Scenario& scenario, const Plan& plan, const ExportOptions& options);

}  // namespace uavplan
