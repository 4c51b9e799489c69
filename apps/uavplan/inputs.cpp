// Loading a scenario and a plan that belongs to it, shared by verify, export and report.
#include <iostream>

#include "commands.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan::cli {

namespace {

// The plan file, every UAV of it in the scenario; throws InputError.
Plan plan_of(const Scenario& sc, const std::string& scenario_path, const std::string& plan_path) {
  Plan plan = load_plan(plan_path);
  for (std::size_t i = 0; i < plan.uavs.size(); ++i)
    if (!sc.find_uav(plan.uavs[i].id))
      throw InputError(plan_path, 0, "uavs[" + std::to_string(i) + "].id",
                       "UAV '" + plan.uavs[i].id + "' is not in the scenario " + scenario_path);
  return plan;
}

// Runs `load`; bad input is printed on stderr and returns false.
template <typename Load>
bool reported(Load&& load) {
  try {
    load();
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return false;
  }
  return true;
}

}  // namespace

bool load_scenario_and_plan(const std::string& scenario_path, const std::string& plan_path, Scenario& sc, Plan& plan) {
  return reported([&] {
    sc = load_scenario(scenario_path);
    plan = plan_of(sc, scenario_path, plan_path);
  });
}

bool load_plan_of(const Scenario& sc, const std::string& scenario_path, const std::string& plan_path, Plan& plan) {
  return reported([&] { plan = plan_of(sc, scenario_path, plan_path); });
}

}  // namespace uavplan::cli
