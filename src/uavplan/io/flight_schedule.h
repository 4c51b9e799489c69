// When to start each exported mission: so that its UAV is where the plan has it when the plan's
// clock says, its take-off included. The take-off is the autopilot's own (its spool-up, its climb
// speed), not the plan's: an airborne start's take-off happens before t = 0 and takes what the
// autopilot takes; a plan that takes off from the ground times its climb at cruise speed, so its
// mission starts earlier by what the autopilot's climb takes more.
// Time model (ArduCopter 4.7, measured in its SITL with the parameters it lists, see
// docs/decisions/0020-flown-timing.md): 4.2 s from arming to lifting off (the motors' spool-up),
// the climb at WPNAV_SPEED_UP (2.5 m/s, or what the route's climbs need) plus 0.4 s to reach that
// speed and stop at the top (WPNAV_ACCEL_Z 2.5 m/s^2), 1.3 s there to the next leg's start, then
// the leg's S-curve from rest (WPNAV_ACCEL 5 m/s^2, WPNAV_JERK 20 m/s^3: the top of their
// ranges, the nearest an autopilot comes to the plan's speed changes; ArduCopter's defaults, 2.5
// and 1, lose seconds at every turn), which leaves it behind a start at cruise speed by half its
// duration: the mission is started that much earlier too, so that it is on the plan's clock once
// at speed. Other firmwares and fixed wings keep the export's own timing (each leg at cruise
// speed): no simulator here to measure them.
#pragma once

#include <string>
#include <vector>

#include "uavplan/io/export.h"
#include "uavplan/io/flight_export.h"

namespace uavplan {

inline constexpr double kCopterLiftoff_s = 4.2;        // arming to lifting off (ArduCopter SITL)
inline constexpr double kCopterClimb_mps = 2.5;        // WPNAV_SPEED_UP default
inline constexpr double kCopterDescent_mps = 1.5;      // WPNAV_SPEED_DN default
inline constexpr double kCopterClimbRamps_s = 0.4;     // a climb's S-curve to and from its speed (measured)
inline constexpr double kCopterWaypointPause_s = 1.3;  // on a reached waypoint, to moving (measured)
inline constexpr double kCopterAccel_mps2 = 5.0;       // WPNAV_ACCEL (default 2.5): the range's top
inline constexpr double kCopterJerk_mps3 = 20.0;       // WPNAV_JERK (default 1): the range's top
inline constexpr double kCopterAccelZ_mps2 = 2.5;      // WPNAV_ACCEL_Z (default 1): terrain-following slopes
inline constexpr double kCopterLandAltLow_m = 10.0;    // LAND_ALT_LOW default: NAV_LAND's slow final metres
inline constexpr double kCopterLandSpeed_mps = 0.5;    // LAND_SPEED default: below LAND_ALT_LOW

// How far behind a start at `speed_mps` a copter at rest falls while it reaches that speed on
// its S-curve (jerk-limited, then acceleration-limited): half the ramp's duration.
double copter_ramp_lag_s(double speed_mps);

// The shortest leg on which ArduCopter was measured to take up a speed commanded as the leg
// begins, from `speed_mps` (docs/decisions/0020-flown-timing.md): the longer of 25 m and 5 s at
// that speed. On a shorter leg flown through a slow-down comes at the leg's end and a speed-up a
// leg late.
double copter_speed_change_leg_m(double speed_mps);

struct ScheduledStart {
  std::string id;
  double start_s = 0.0;                           // on the plan's clock: when the mission is started (armed, in AUTO)
  double flight_s = 0.0;                          // from its start to the end of its exported flight
  VehicleKind vehicle = VehicleKind::multirotor;  // as exported
  // The firmware parameters the timing assumes, to be set on the vehicle (ArduCopter's: by name,
  // in the parameter's own units); empty where the export's own timing holds.
  std::vector<std::pair<std::string, double>> parameters;
};

// Whether a mission is timed as ArduCopter flies it (its horizontal waypoint speed, its ramps and
// holds), else by the export's own timing.
bool arducopter_timing(const ExportOptions& options);

// ArduCopter's climb and descent speeds for a flight: its defaults, or what the steepest climb
// and descent between its take-off and landing need (10 % over, in whole 10 cm/s).
struct CopterVerticalSpeeds {
  double up_mps = kCopterClimb_mps, down_mps = kCopterDescent_mps;
};
CopterVerticalSpeeds copter_vertical_speeds(const ExportedUav& uav);

// Fixed wing: the firmwares hold an equivalent airspeed (ArduPlane's AIRSPEED_* and
// DO_CHANGE_SPEED, PX4's FW_AIRSPD_*: what a pitot reads), the plan's speeds are true (over the
// ground in still air). EAS = TAS sqrt(rho / rho0), rho in the ISA troposphere at the altitude
// above sea level: 0.966 at 700 m, 0.776 at 5,000 m.
double equivalent_per_true_airspeed(double alt_amsl_m);

std::vector<ScheduledStart> flight_schedule(const Scenario& scenario, const VerifiedExport& flights,
                                            const ExportOptions& options);

// schedule.json: {"clock": ..., "uavs": [{"id", "start_s", "flight_s", "files": [...]}]}, the
// files each UAV's mission is in (by UAV id, from the export's files).
std::string schedule_json(const std::vector<ScheduledStart>& schedule,
                          const std::vector<std::pair<std::string, std::string>>& files_by_uav);

// schedule.json as the file an export writes beside `files` (naming each UAV's among them).
ExportFile schedule_file(const std::vector<ScheduledStart>& schedule, const std::vector<ExportFile>& files);

}  // namespace uavplan
