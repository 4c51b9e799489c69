// uavplan: plans routes for UAVs, groups and formations, verifies them, benchmarks planners.
#include <cstdio>
#include <iostream>
#include <new>

#include "commands.h"
#include "companion.h"
#include "uavplan/io/files.h"

namespace {

int run_command_line(int argc, char** argv) {
  using namespace uavplan::cli;
  remember_command_line(argc, argv);
  install_terminal_filter();
  die_with_batch();
  CLI::App app{"uavplan: route planning for UAVs, UAV groups and formations, with verification"};
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  uavplan plan scenarios/demo.yaml -o out          plan, verify, write out/plan.json\n"
      "  uavplan plan scenarios/demo.yaml --set cell_m=5  override a planner parameter\n"
      "  uavplan verify scenarios/demo.yaml out/plan.json check a plan, list every violation\n"
      "  uavplan export scenarios/demo.yaml out/plan.json --format qgc -o out   QGroundControl .plan per UAV\n"
      "  uavplan report scenarios/demo.yaml out/plan.json -o out/report.html  HTML report, 3-D view\n"
      "  uavplan info scenarios/demo.yaml                 summarise a scenario's world\n"
      "  uavplan bench world                              world-query benchmark table\n"
      "  uavplan batch sweep.yaml -o results              a sweep of runs on every core, results.csv\n"
      "Exit codes: 0 solved (or plan holds), 1 not solved (or violations), 2 bad input, 3 output not written\n"
      "(a full disk, permissions), 130 interrupted.");
  // Usage errors are one line too, like every bad input.
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return "uavplan: " + std::string(e.what()) + "\n"; });
  std::function<int()> run;
  add_plan_command(app, run);
  add_verify_command(app, run);
  add_info_command(app, run);
  add_bench_command(app, run);
  add_export_command(app, run);
  add_report_command(app, run);
  add_batch_command(app, run);
  add_fly_command(app, run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  try {
    return run ? run() : kExitBadInput;
  } catch (const uavplan::OutputError& e) {
    std::cerr << "uavplan: " << e.what() << "; nothing written\n";
    return kExitOutputError;
  } catch (const std::bad_alloc&) {
    std::cerr << "uavplan: out of memory: the input asks for more than this machine has (see --max-memory)\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "uavplan: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_command_line(argc, argv);
  } catch (...) {  // not a std::exception: nothing the commands throw on purpose
    std::fputs("uavplan: internal error: an unexpected exception\n", stderr);
    return uavplan::cli::kExitBadInput;
  }
}
