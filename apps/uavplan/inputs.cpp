// Loading a scenario and a plan that belongs to it, shared by verify, export and report.
#include <iostream>

#include "commands.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan::cli {

bool load_scenario_and_plan(const std::string& scenario_path, const std::string& plan_path, Scenario& sc, Plan& plan) {
  try {
    sc = load_scenario(scenario_path);
    plan = load_plan(plan_path);
    for (std::size_t i = 0; i < plan.uavs.size(); ++i)
      if (!sc.find_uav(plan.uavs[i].id))
        throw InputError(plan_path, 0, "uavs[" + std::to_string(i) + "].id",
                         "UAV '" + plan.uavs[i].id + "' is not in the scenario " + scenario_path);
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return false;
  }
  return true;
}

}  // namespace uavplan::cli
