// Mission types are a registry, like planners: each type is one file pair that plans a whole
// scenario into a Plan; plan_mission (mission_planner.h) looks the type up and does the rest.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/stop.h"

namespace uavplan {

struct MissionOptions {
  std::optional<std::string> algorithm;  // overrides the scenario's planner
  Params params;                         // merged over the scenario's planner params
  std::uint64_t seed = 1;
  StopCondition stop;
  double max_sample_dt_s = 1.0;  // longest time between trajectory samples
  double delay_step_s = 1.0;     // departure delays are tried in these steps
  std::function<void(std::size_t done, std::size_t total)> progress;
};

// Why a UAV has no plan when the stop condition ended the run first.
inline constexpr const char* kStoppedMessage = "stopped (time limit or interrupt) before it was planned";

// Per UAV of a scenario that stands on the ground at its start or goal: the point on the ground
// it lifts off from (its scenario start) and the one it lands on (under its touch-down point).
// The scenario a mission plans has the UAV lifted off and touching down (planning_view.h).
struct GroundPoints {
  std::vector<std::optional<Vec3>> start, goal;
};

// What a mission plans with: the options, the planner chosen for it with its parameters, the
// parameters the mission reads itself (Mission::parameters()) and the ground legs' ends.
struct MissionContext {
  const MissionOptions& options;
  std::string algorithm;
  Params params;
  Params mission_params;
  GroundPoints ground;
};

class Mission {
 public:
  virtual ~Mission() = default;
  // The planners this mission plans with, the default first; empty: any registered planner.
  virtual std::vector<std::string> algorithms() const { return {}; }
  // The planner it plans with when none is asked for.
  virtual std::string default_algorithm() const { return algorithms().empty() ? "astar" : algorithms().front(); }
  // Keys of planner.params (and --set) that the mission reads itself, not its planner.
  virtual std::vector<std::string> parameters() const { return {}; }
  // Whether the mission flies UAVs' take-off and landing legs within its own timing (from
  // MissionContext::ground); otherwise they are added around its plan.
  virtual bool times_ground_legs() const { return false; }
  // Appends one UavPlan per scenario UAV, in scenario order. Throws std::invalid_argument for
  // bad parameters or a malformed problem.
  virtual void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const = 0;
};

// The mission registered for a type, or nullptr when none is.
const Mission* find_mission(MissionType type);
// The registered mission types' names in registry order ("independent, route, ... or X"), for
// messages that list them.
std::string mission_type_list();

// The planner a mission plans with: the one asked for (--algorithm, else the scenario's when it
// names one), else the mission's default. Throws std::invalid_argument when the one asked for
// cannot plan this mission, naming those that can.
std::string mission_algorithm(const Scenario& scenario, const std::optional<std::string>& asked);

}  // namespace uavplan
