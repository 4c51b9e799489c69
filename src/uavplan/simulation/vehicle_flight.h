// How a UAV flies its waypoints: a point mass at cruise speed (time_route), or, for a UAV with a
// `model`, P5's autopilot model (vehicle/autopilot.h) following them, the trajectory then what
// the model flew. Waypoint switching: a waypoint is passed within the switch radius (the larger
// of the turn radius at cruise and 2 v tau_heading) or once the UAV is past it along its leg; the
// last is caught within max(2 v h, v tau_heading), and the trajectory ends straight onto it.
#pragma once

#include <span>

#include "uavplan/simulation/trajectory.h"
#include "uavplan/vehicle/autopilot.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {

// The model a UAV with `model` flies through, its limits from the UAV (speed range, turn and
// climb rate limits; none: unlimited).
AutopilotModel autopilot_of(const UavSpec& u);

// Its flight of `waypoints` departing at depart_s (holding at the first before), samples at most
// max_dt_s apart (1 s for the model when max_dt_s is 0). Empty when the model cannot reach the last
// waypoint (it circles it: a turn radius wider than the route allows).
// Waypoints equal to one of `fly_over` are flown over (via points), not turned short of.
Trajectory fly_route(const UavSpec& u, std::span<const Vec3> waypoints, double depart_s, double max_dt_s,
                     std::span<const Vec3> fly_over = {});

}  // namespace uavplan
