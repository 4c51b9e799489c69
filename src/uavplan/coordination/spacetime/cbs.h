// Conflict-based search (Sharon et al. 2015) and its bounded-suboptimal form ECBS (Barer et al.
// 2014), one implementation: w = 1 is CBS. The high level takes the first conflict of a node's
// paths and splits it into two children, each forbidding one of the two agents its part of the
// conflict (a vertex at a time, or a move in a step) and planning that agent again; the low level
// is the focal space-time search, avoiding the other agents' paths. A node's lower bound is the
// sum of its agents' bounds; nodes whose cost is within w of the least bound open are taken by
// fewest conflicts.
#pragma once

#include "uavplan/coordination/spacetime/mapf.h"
#include "uavplan/coordination/spacetime/space_time_model.h"

namespace uavplan {

// At most `most_nodes` high-level nodes (0: no limit) within `stop`.
MapfResult solve_cbs(const SpaceTimeModel& model, double w, const StopCondition& stop, std::uint64_t most_nodes = 0);

}  // namespace uavplan
