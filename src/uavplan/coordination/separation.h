// Separation between UAVs: how far apart two UAVs must stay (at their goals too: UAVs sharing a
// goal end at distinct points, arrival_points.h).
#pragma once

#include "uavplan/coordination/scenario.h"

namespace uavplan {

// The distance UAVs a and b must keep: the mission's separation, and never less than the sum
// of their radii.
double required_separation_m(const Scenario& scenario, const UavSpec& a, const UavSpec& b);

}  // namespace uavplan
