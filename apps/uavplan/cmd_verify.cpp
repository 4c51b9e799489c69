// uavplan verify SCENARIO PLAN: print every violation; exit 0 when the plan holds.
#include <iostream>

#include "commands.h"
#include "uavplan/core/text.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan::cli {
namespace {

int run_verify(const std::string& scenario_path, const std::string& plan_path) {
  Scenario sc;
  Plan plan;
  if (!load_scenario_and_plan(scenario_path, plan_path, sc, plan)) return kExitBadInput;
  const auto violations = verify_plan(sc, plan);
  for (const auto& v : violations) std::cout << describe(v) << "\n";
  if (violations.empty()) {
    std::cout << "plan holds: " << count_text(plan.uavs.size(), "UAV") << ", no violation\n";
    return kExitOk;
  }
  std::cout << violations.size() << " violation" << (violations.size() == 1 ? "" : "s") << "\n";
  return kExitNotSolved;
}

}  // namespace

void add_verify_command(CLI::App& app, std::function<int()>& run) {
  auto scenario = std::make_shared<std::string>();
  auto plan = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("verify", "Check a plan against its scenario and print every violation");
  cmd->add_option("scenario", *scenario, "Scenario file")->required();
  cmd->add_option("plan", *plan, "Plan file (plan.json)")->required();
  cmd->footer("Example: uavplan verify scenarios/demo.yaml out/plan.json");
  cmd->callback([scenario, plan, &run] { run = [scenario, plan] { return run_verify(*scenario, *plan); }; });
}

}  // namespace uavplan::cli
