// Mission types are a registry, like planners: each type is one file pair that plans a whole
// scenario into a Plan; plan_mission (mission_planner.h) looks the type up and does the rest.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

// Why a UAV has no plan when the stop condition ended the run first.
inline constexpr const char* kStoppedMessage = "stopped (time limit or interrupt) before it was planned";

// What a mission plans with: the options, the planner chosen for it with its parameters, and
// the parameters the mission reads itself (Mission::parameters()).
struct MissionContext {
  const MissionOptions& options;
  std::string algorithm;
  Params params;
  Params mission_params;
};

class Mission {
 public:
  virtual ~Mission() = default;
  // The planners this mission plans with, the default first; empty: any registered planner.
  virtual std::vector<std::string> algorithms() const { return {}; }
  // Keys of planner.params (and --set) that the mission reads itself, not its planner.
  virtual std::vector<std::string> parameters() const { return {}; }
  // Appends one UavPlan per scenario UAV, in scenario order. Throws std::invalid_argument for
  // bad parameters or a malformed problem.
  virtual void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const = 0;
};

// The mission registered for a type, or nullptr when none is.
const Mission* find_mission(MissionType type);

}  // namespace uavplan
