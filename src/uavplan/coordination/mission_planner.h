// Plans a whole scenario: each UAV's route by the chosen planner, then times the routes so that
// UAVs keep their separation and stay clear of moving obstacles (prioritised departure delays:
// each UAV in turn takes the earliest departure that conflicts with none planned before it).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "uavplan/coordination/plan.h"
#include "uavplan/coordination/scenario.h"
#include "uavplan/core/stop.h"

namespace uavplan {

struct MissionOptions {
  std::optional<std::string> algorithm;  // overrides the scenario's planner
  Params params;                         // merged over the scenario's planner params
  std::uint64_t seed = 1;
  StopCondition stop;
  double max_sample_dt_s = 1.0;          // longest time between trajectory samples
  double delay_step_s = 1.0;             // departure delays are tried in these steps
  std::function<void(std::size_t done, std::size_t total)> progress;
};

// Throws std::invalid_argument for an unknown planner, bad parameters or a malformed problem.
Plan plan_mission(const Scenario& scenario, const MissionOptions& options);

// The distance UAVs a and b must keep: the mission's separation, and never less than the sum
// of their radii.
double required_separation_m(const Scenario& scenario, const UavSpec& a, const UavSpec& b);

// Until when the separation of a and b is checked. UAVs given the same goal (within the
// separation) meet there by design: their separation counts until the first of them comes
// within the separation of that goal. Otherwise always (+inf).
double separation_horizon_s(const Scenario& scenario, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                            const Trajectory& tb);

}  // namespace uavplan
