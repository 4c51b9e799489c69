// formation_mission's task points, as the contract checks them: the formation's reference (the
// mean position of the airborne UAVs: more than kAirborneAbove_m above the airfield, between
// their first and last rows) passes within each point's radius, in order, flying within
// kTaskHeadingTolerance_deg of its entry heading.
#pragma once

#include <vector>

#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

// Reached when the formation's reference passes within radius_m of the position flying within
// kTaskHeadingTolerance_deg of the entry heading (when one is given).
struct TaskPoint {
  Vec3 position = Vec3::Zero();
  std::optional<double> entry_heading_rad;
  double radius_m = 1000.0;
};
inline constexpr double kTaskHeadingTolerance_deg = 15.0;

// formation_mission's section: the shape, the task points in order, the communication topology
// a_ij of the consensus control (rows per UAV in scenario order; empty: the complete graph).
// The airfield is MissionSpec's (the exports fly its runway).
struct PhasedFormationSection : FormationShapeSection {
  std::vector<TaskPoint> task_points;
  std::vector<std::vector<double>> topology;
};
// The scenario's formation_mission section (an empty one where it has none).
const PhasedFormationSection& phased_section(const Scenario& scenario);

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
