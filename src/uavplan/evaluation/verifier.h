// The verifier: checks a plan against its scenario and reports every violation with the UAV,
// the time and the place. A plan that is not verified is never `solved` (finalize_plan).
// A UAV may start and end on the ground (z = the terrain there, or the bottom of the bounds):
// its legs from and to the ground (up to the first row off the ground, from the last one) keep
// their distance from obstacles, but not from the ground they leave or reach within the UAV's
// radius and clearance, and the climb and turn limits and min_agl do not hold on them.
#pragma once

#include <optional>
#include <string>
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
  obstacle,      // static obstacles and terrain, after inflation by the UAV radius and clearance
  low_altitude,  // below the UAV's min_agl above the ground (but taking off and landing)
  moving_obstacle,
  separation,  // two UAVs closer than the mission's separation (or their radii)
  turn,
  climb,
  speed,
  via_point,       // a via point missed or visited out of order
  length_spread,   // rendezvous: route lengths differ by more than the tolerance
  arrival_spread,  // formation: arrival times differ by more than arrival_tolerance_s
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

std::vector<Violation> verify_plan(const Scenario& sc, const Plan& plan);

// Verifies, marks every UAV with a violation as failed (with the first violation as its
// message), recomputes the plan's status and metrics; returns the violations.
std::vector<Violation> finalize_plan(const Scenario& sc, Plan& plan);

}  // namespace uavplan
