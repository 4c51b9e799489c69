// Violations of a plan's rules, as the verifier (evaluation/verifier.h) reports them: the data
// every mission's own checks (Mission::check_uav, check_pair, check_plan) add to.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"

namespace uavplan {

// How far a route mission's arrival at a via point may be off its entry heading.
inline constexpr double kEntryHeadingTolerance_deg = 1.0;

enum class ViolationKind {
  not_planned,  // a UAV has no trajectory, or the plan lacks a scenario UAV
  unknown_uav,  // the plan names a UAV the scenario lacks
  trajectory,   // non-finite values, time going backwards, jumps
  start,        // does not begin at the UAV's start
  goal,         // does not end at the UAV's goal
  bounds,
  ceiling,
  obstacle,       // static obstacles and terrain, after inflation by the UAV radius and clearance
  low_altitude,   // below the UAV's min_agl above the ground (but taking off and landing)
  high_altitude,  // above the UAV's max_agl above the ground (but taking off and landing)
  moving_obstacle,
  separation,  // two UAVs closer than the mission's separation (or their radii)
  turn,
  climb,
  speed,
  via_point,       // a via point missed or visited out of order
  length_spread,   // rendezvous: route lengths differ by more than the tolerance
  arrival_spread,  // formation: arrival times differ by more than arrival_tolerance_s
  runway,          // formation_mission: two UAVs on the runway at once (contract/runway.h)
};

std::string_view to_string(ViolationKind k);

struct Violation {
  ViolationKind kind;
  std::string uav;  // empty for a mission-level violation
  std::optional<double> t_s;
  std::optional<Vec3> where;
  std::string message;
};

// One line: "u1 obstacle t=12.30 s at (10.0, 2.0, 5.0): ...".
std::string describe(const Violation& v);

// Tolerances of the checks: positions (start, goal, via points) within kPositionTolerance_m,
// distances and angles may undershoot by kDistanceTolerance_m / kAngleTolerance_rad.
inline constexpr double kPositionTolerance_m = 1e-3;
inline constexpr double kDistanceTolerance_m = 1e-6;

using Violations = std::vector<Violation>;

// Appends one violation.
void add_violation(Violations& out, ViolationKind kind, const std::string& uav, std::optional<double> t_s,
                   std::optional<Vec3> where, std::string message);

// The UAVs of a plan that have a trajectory, with their scenario entries, in scenario order.
using FlownUavs = std::vector<std::pair<const UavSpec*, const UavPlan*>>;

}  // namespace uavplan
