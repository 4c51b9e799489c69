// The local layer's parameters, shared by the missions that fly in the closed loop: `local`
// (improved_rrt, default, or rrt: P1's local replanner or its baseline) and `window_m` (the route
// ahead each UAV checks; 0: its sensor range).
#pragma once

#include "uavplan/coordination/mission.h"
#include "uavplan/planning/sampling/rrt.h"

namespace uavplan {

struct LocalLayer {
  RrtOptions rrt;
  double window_m = 0.0;  // 0: each UAV's sensor range
};

// Reads `local` and `window_m` from the mission's parameters; throws std::invalid_argument, also
// for a parameter of the mission's that no one reads.
LocalLayer local_layer(const MissionContext& ctx);
// Reads them through `r`, leaving the mission's other parameters to the caller.
LocalLayer local_layer(const MissionContext& ctx, ParamReader& r);

}  // namespace uavplan
