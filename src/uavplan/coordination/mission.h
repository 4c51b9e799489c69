// Mission types are a registry, like planners: each type is one room of coordination/ whose
// Mission declares the keys of the scenario's `mission` section it reads, reads them, plans a
// whole scenario into a Plan and adds its own rules to the verifier's. plan_mission
// (mission_planner.h), the scenario reader (io/scenario_io.cpp) and the verifier
// (evaluation/verifier.cpp) look the type up and do the rest.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/coordination/contract/section.h"
#include "uavplan/coordination/contract/violation.h"
#include "uavplan/core/stop.h"
#include "uavplan/planning/registry.h"

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

// One key of a mission type's section as a row of its declaration: what the scenario reader
// accepts, what `uavplan info --missions` lists and docs/formats.md's table shows.
struct MissionKey {
  std::string key;
  std::string type;           // in the scenario's words: "number", "[x, y, z]", "list of ...", ...
  std::string default_value;  // as text; empty: required when the type is planned
  std::string unit;           // "m", "s", "deg"; empty: none
  std::string doc;            // one sentence
};

// The keys of the `mission` section every type reads (io/scenario_io.cpp).
const std::vector<MissionKey>& common_mission_keys();

// How an export verifies the flights it writes (io/flight_export.cpp): as independent flights
// (via points and the mission's own rules are the plan's, verified already), or under the
// mission's own pair rule as well (an airfield's: separation in the air, bodies on the ground).
enum class ExportRules { independent, own_pair_rule };

// Everything about a mission type that is not code, declared once by its room: the reader, the
// planner's choice, metrics, exports, `info` and the docs read it.
struct MissionDeclaration {
  std::string name;  // the scenario's mission.type
  std::string summary;
  std::vector<MissionKey> keys;         // its section's keys besides the common ones
  std::vector<std::string> algorithms;  // the planners it plans with, default first; empty: any
  std::string default_algorithm = "astar";
  std::vector<std::string> parameters;  // keys of planner.params (and --set) it reads itself
  bool needs_goals = true;              // every UAV needs a goal
  bool flies_homes = false;             // a UAV may take off from its `home` and land there
  // It flies the UAVs' take-off and landing legs within its own timing (MissionContext::ground);
  // otherwise they are added around its plan.
  bool times_ground_legs = false;
  // Its UAVs start and end on its own ground (an airfield): planners keep no default height
  // above the ground for it (planning_view.h).
  bool own_ground = false;
  ExportRules export_rules = ExportRules::independent;
  std::vector<std::string> metrics;  // plan metrics it adds to every plan's (metrics.cpp)
};

class Mission {
 public:
  virtual ~Mission() = default;
  virtual const MissionDeclaration& declaration() const = 0;

  // Reading the scenario.
  // Reads its keys into scenario.mission once the world, the UAVs and the common keys are read;
  // checks what they ask of the UAVs (`uavs`: the scenario's list). Fails through the sections.
  virtual void read_section(const Section& /*mission*/, const Section& /*uavs*/, Scenario& /*scenario*/) const {}
  // What `info` says of the scenario's section after the type and separation (", 3 via points").
  virtual std::string describe(const Scenario& /*scenario*/) const { return {}; }

  // Planning.
  // Why the planner cannot plan this scenario's mission (empty: it can), beside the declared
  // algorithms; a route's via points need planners that pass them.
  virtual std::string planner_refusal(const Scenario& /*scenario*/, const PlannerInfo& /*planner*/) const { return {}; }
  // The planner it plans this scenario with when none is asked for.
  virtual std::string default_algorithm(const Scenario& /*scenario*/) const { return declaration().default_algorithm; }
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
  // The distance of two UAVs its separation rule measures (metrics' min_separation_m); none: the
  // closest approach of their trajectories.
  virtual std::optional<double> pair_distance_m(const Scenario& /*scenario*/, const UavSpec& /*a*/,
                                                const Trajectory& /*ta*/, const UavSpec& /*b*/,
                                                const Trajectory& /*tb*/) const {
    return std::nullopt;
  }
  // On the whole plan (the UAVs that have a trajectory).
  virtual void check_plan(const Scenario& /*scenario*/, const FlownUavs& /*flown*/, Violations& /*out*/) const {}
};

// The mission registered under a name, or nullptr when none is.
const Mission* find_mission(std::string_view type);
// Every registered mission, the built-in ones first, in registry order.
std::vector<const Mission*> missions();
// The registered mission types' names in registry order ("independent, route, ... or X"), for
// messages that list them.
std::string mission_type_list();

// Adds a mission type (a mission's room: `static MissionRegistration r{std::make_unique<M>()};`
// in its file). Throws std::invalid_argument for a name already registered or one that is not
// [a-z0-9_]+, or a key of its declaration that a common key or another key already has.
void register_mission(std::unique_ptr<const Mission> mission);
struct MissionRegistration {
  explicit MissionRegistration(std::unique_ptr<const Mission> mission) { register_mission(std::move(mission)); }
};

// The declarations as text: `info --missions` (markdown = false) and docs/formats.md's table of
// mission types and keys (markdown = true).
std::string mission_catalog_text(bool markdown);

// The planner a mission plans with: the one asked for (--algorithm, else the scenario's when it
// names one), else the mission's default. Throws std::invalid_argument when the one asked for
// cannot plan this mission, naming those that can.
std::string mission_algorithm(const Scenario& scenario, const std::optional<std::string>& asked);
// Why the planner cannot plan the scenario's mission (empty: it can).
std::string planner_refusal(const Scenario& scenario, const PlannerInfo& planner);

}  // namespace uavplan
