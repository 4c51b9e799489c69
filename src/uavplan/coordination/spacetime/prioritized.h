// Prioritised planning (Silver 2005; Erdmann and Lozano-Perez 1987): agents one after another,
// each around the paths of those before it (their vertices, swaps, and goals they stay at). Fast
// and incomplete: when an agent finds no path, the next order puts it first (Bennewitz et al.
// 2002's idea of searching orders, here the simplest deterministic rule), up to `orders` tries.
#pragma once

#include "uavplan/coordination/spacetime/mapf.h"
#include "uavplan/coordination/spacetime/space_time_model.h"

namespace uavplan {

MapfResult solve_prioritized(const SpaceTimeModel& model, int orders, const StopCondition& stop);

}  // namespace uavplan
