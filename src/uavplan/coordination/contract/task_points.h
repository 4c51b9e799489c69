// formation_mission's task points, as the contract checks them: the formation's reference (the
// mean position of the airborne UAVs: more than kAirborneAbove_m above the airfield, between
// their first and last rows) passes within each point's radius, in order, flying within
// kTaskHeadingTolerance_deg of its entry heading.
#pragma once

#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

// The reference at the merged row times of the trajectories (times with no UAV airborne left out).
Trajectory formation_reference(const Scenario& scenario, const std::vector<const Trajectory*>& trajectories);

struct TaskVisit {
  bool reached = false;
  double t_s = 0.0;
  double miss_m = 0.0;             // the reference's closest distance where it counts
  double heading_error_rad = 0.0;  // there
};

// Per task point, in order: the first pass within its radius at its heading after the previous.
std::vector<TaskVisit> task_visits(const Scenario& scenario, const Trajectory& reference);

}  // namespace uavplan
