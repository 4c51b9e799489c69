// uavplan report SCENARIO PLAN [--flown FLOWN] -o FILE: the self-contained HTML report of a plan
// (and of its flight, drawn beside it).
#include <iostream>

#include "commands.h"
#include "uavplan/core/text.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/io/files.h"
#include "uavplan/io/report.h"

namespace uavplan::cli {
namespace {

struct ReportArgs {
  std::string scenario, plan, out = "out/report.html", flown;
};

int run_report(const ReportArgs& a) {
  check_output_dir(a.out);
  Scenario sc;
  Plan plan;
  if (!load_scenario_and_plan(a.scenario, a.plan, sc, plan)) return kExitBadInput;
  const auto violations = verify_plan(sc, plan);
  ReportOptions opt;
  Plan flown;
  if (!a.flown.empty()) {
    if (!load_plan_of(sc, a.scenario, a.flown, flown)) return kExitBadInput;
    opt.flown = &flown;
  }
  write_file_atomic(a.out, report_html(sc, plan, violations, opt));
  std::cout << "wrote " << a.out << " (" << count_text(plan.uavs.size(), "UAV") << ", "
            << (violations.empty() ? std::string("plan holds") : count_text(violations.size(), "violation")) << ")\n";
  return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, std::function<int()>& run) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd =
      app.add_subcommand("report", "Write a self-contained HTML report: 3-D view, charts, metrics, verification");
  cmd->add_option("scenario", args->scenario, "Scenario file")->required();
  cmd->add_option("plan", args->plan, "Plan file (plan.json)")->required();
  cmd->add_option("-o,--out", args->out, "Report file (default: out/report.html)");
  cmd->add_option("--flown", args->flown, "A flight of the plan (uavplan fly's flown.json): drawn beside the routes");
  cmd->footer("Example: uavplan report scenarios/demo.yaml out/plan.json -o out/report.html");
  cmd->callback([args, &run] { run = [args] { return run_report(*args); }; });
}

}  // namespace uavplan::cli
