// Plan files (JSON, format "uavplan-plan", version 1 of the public contract).
#pragma once

#include <string>

#include "uavplan/coordination/contract/plan.h"

namespace uavplan {

struct PlanWriteOptions {
  // Wall-clock timing changes from run to run; left out by default so that the same scenario
  // and seed give the same bytes.
  bool include_timing = false;
};

// Waypoints, trajectories and lengths are written at full double precision (shortest
// round-trip form), so the file holds exactly the plan that was verified; metrics are rounded
// to 1e-6.
std::string plan_to_json(const Plan& plan, const PlanWriteOptions& options = {});

// Throws InputError naming the file and the key for malformed plans.
Plan parse_plan(const std::string& text, const std::string& source_name);
Plan load_plan(const std::string& path);

}  // namespace uavplan
