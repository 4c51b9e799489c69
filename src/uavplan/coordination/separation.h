// Separation between UAVs: how far apart two UAVs must stay, and until when it counts.
#pragma once

#include "uavplan/coordination/scenario.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

// The distance UAVs a and b must keep: the mission's separation, and never less than the sum
// of their radii.
double required_separation_m(const Scenario& scenario, const UavSpec& a, const UavSpec& b);

// Until when the separation of a and b is checked. UAVs given the same goal (within the
// separation) meet there by design: their separation counts until the first of them comes
// within the separation of that goal. Otherwise always (+inf).
double separation_horizon_s(const Scenario& scenario, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                            const Trajectory& tb);

}  // namespace uavplan
