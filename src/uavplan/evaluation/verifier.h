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
#include "uavplan/coordination/contract/violation.h"

namespace uavplan {

std::vector<Violation> verify_plan(const Scenario& sc, const Plan& plan);

// Verifies, marks every UAV with a violation as failed (with the first violation as its
// message), recomputes the plan's status and metrics; returns the violations.
std::vector<Violation> finalize_plan(const Scenario& sc, Plan& plan);

}  // namespace uavplan
