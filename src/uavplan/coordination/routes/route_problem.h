// What a routes mission asks of each UAV: its start and goal, a route mission's via points, and
// with a home its own start and goal visited on the way.
#pragma once

#include <cstddef>

#include "uavplan/coordination/mission.h"
#include "uavplan/planning/problem.h"

namespace uavplan {

// The planner's problem for UAV i of `sc` (the planning view's scenario), seeded by the run's seed.
Problem uav_problem(const Scenario& sc, const MissionOptions& opt, const GroundPoints& ground, std::size_t i);

}  // namespace uavplan
