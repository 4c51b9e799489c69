// The mission a UAV flies, as MAVLink mission items, read off its exported flight
// (flight_export.h): a take-off to the top of its take-off leg, a loiter where the trajectory
// holds still (MAV_CMD_NAV_LOITER_TIME, the hold's seconds), a waypoint at every change of
// direction, the planned speed (DO_CHANGE_SPEED: airspeed for fixed wing, ground speed for
// multirotors) before the first leg and before a leg whose speed differs by the options'
// fraction or more, then its end: NAV_LAND at the touch-down point (fixed wing:
// DO_LAND_START before the approach waypoint), the return waypoints and RETURN_TO_LAUNCH,
// NAV_LOITER_UNLIM (radius 0 multirotor, the loiter radius fixed wing), or nothing.
// Positions are WGS84 with altitudes relative to home (on the origin's datum, geo.h).
#pragma once

#include <array>
#include <vector>

#include "uavplan/io/flight_export.h"

namespace uavplan {

inline constexpr int kCmdWaypoint = 16, kCmdLoiterUnlimited = 17, kCmdLoiterTurns = 18, kCmdLoiterTime = 19,
                     kCmdReturn = 20, kCmdLand = 21, kCmdTakeoff = 22, kCmdChangeSpeed = 178, kCmdLandStart = 189;
// MAV_FRAME: GLOBAL (absolute altitude), MISSION (commands without a position), GLOBAL_RELATIVE_ALT,
// GLOBAL_TERRAIN_ALT.
inline constexpr int kFrameGlobal = 0, kFrameMission = 2, kFrameGlobalRelativeAlt = 3, kFrameGlobalTerrainAlt = 10;

// One mission item as MAVLink carries it: params 5-7 are lat, lon (degrees) and altitude for
// items with a position (frame 3, 0 or 10: the altitude above home, sea level or the terrain);
// all zero for DO commands and the return (frame 2).
struct MissionItem {
  int command = kCmdWaypoint;
  int frame = kFrameGlobalRelativeAlt;
  std::array<double, 7> params{};
  double amsl_m = 0.0;  // a positioned item's altitude above mean sea level, whatever its frame
  bool positioned() const { return frame != kFrameMission; }
};

// The frame the options' altitude asks for (AltitudeFrame::standard resolved for the scenario).
// Throws ExportError for the terrain frame with PX4 (its missions take no frame 10).
AltitudeFrame altitude_frame(const Scenario& scenario, const ExportOptions& options);
int mav_frame(AltitudeFrame frame);

// Throws ExportError when the scenario has no origin.
std::vector<MissionItem> mission_items(const Scenario& scenario, const ExportedUav& uav, const ExportOptions& options);

}  // namespace uavplan
