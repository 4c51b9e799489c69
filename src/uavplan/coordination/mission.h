// Mission types are a registry, like planners: each type is one room of coordination/ whose
// Mission declares the keys of the scenario's `mission` section it reads, reads them, plans a
// whole scenario into a Plan and adds its own rules to the verifier's. plan_mission
// (mission_planner.h), the scenario reader (io/scenario_io.cpp) and the verifier
// (evaluation/verifier.cpp) look the type up and do the rest.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/coordination/contract/section.h"
#include "uavplan/coordination/contract/violation.h"
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
  // Per UAV with a home (its start and goal are the ground there): the UAV's own start and goal,
  // visited on the way (before and after the mission's via points); either is left out when it
  // lies straight above home, where the climb from home ends or the descent to it begins.
  struct HomeVisits {
    std::optional<Vec3> start, goal;
  };
  std::vector<std::optional<HomeVisits>> home_visits;
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

// The keys of the `mission` section every type reads (io/scenario_io.cpp): type, separation,
// step_s, goal_spacing.
inline constexpr std::array<const char*, 4> kCommonMissionKeys = {"type", "separation", "step_s", "goal_spacing"};

class Mission {
 public:
  virtual ~Mission() = default;

  // Reading the scenario.
  // The keys of the `mission` section it reads besides kCommonMissionKeys.
  virtual std::vector<const char*> section_keys() const { return {}; }
  // Reads them into scenario.mission once the world, the UAVs and the common keys are read;
  // checks what they ask of the UAVs (`uavs`: the scenario's list). Fails through the sections.
  virtual void read_section(const Section& /*mission*/, const Section& /*uavs*/, Scenario& /*scenario*/) const {}
  // Whether every UAV needs a goal.
  virtual bool needs_goals() const { return true; }

  // Planning.
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

  // Its rules in the verifier (evaluation/verifier.cpp), beside the rules of every plan.
  // On one UAV's trajectory.
  virtual void check_uav(const Scenario& /*scenario*/, const UavSpec& /*uav*/, const Trajectory& /*trajectory*/,
                         Violations& /*out*/) const {}
  // Separation of two UAVs that come nearer than `need_m` by their swept boxes; by default the
  // closest approach of their trajectories.
  virtual void check_pair(const Scenario& scenario, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                          const Trajectory& tb, double need_m, Violations& out) const;
  // On the whole plan (the UAVs that have a trajectory).
  virtual void check_plan(const Scenario& /*scenario*/, const FlownUavs& /*flown*/, Violations& /*out*/) const {}
};

// The mission registered for a type, or nullptr when none is.
const Mission* find_mission(MissionType type);
// The registered mission types, in registry order.
std::vector<MissionType> mission_types();
// The registered mission types' names in registry order ("independent, route, ... or X"), for
// messages that list them.
std::string mission_type_list();

// The planner a mission plans with: the one asked for (--algorithm, else the scenario's when it
// names one), else the mission's default. Throws std::invalid_argument when the one asked for
// cannot plan this mission, naming those that can.
std::string mission_algorithm(const Scenario& scenario, const std::optional<std::string>& asked);
// Whether the scenario is a route whose via points require entry headings (pso_mpc plans it).
bool route_with_entry_headings(const Scenario& scenario);

}  // namespace uavplan
