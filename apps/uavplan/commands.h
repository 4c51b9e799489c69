// The command-line tool: one small file per subcommand. Exit codes: 0 solved / plan holds,
// 1 not solved / violations, 2 bad input.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "uavplan/coordination/plan.h"
#include "uavplan/coordination/scenario.h"

namespace uavplan::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitNotSolved = 1;
inline constexpr int kExitBadInput = 2;

// Each registers its subcommand on the app and sets `run` to the action to take when chosen.
void add_plan_command(CLI::App& app, std::function<int()>& run);
void add_verify_command(CLI::App& app, std::function<int()>& run);
void add_info_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);
void add_export_command(CLI::App& app, std::function<int()>& run);
void add_report_command(CLI::App& app, std::function<int()>& run);

// Loads both and checks that every plan UAV is in the scenario; on bad input prints the one-line
// error on stderr and returns false (the caller exits with kExitBadInput).
bool load_scenario_and_plan(const std::string& scenario_path, const std::string& plan_path, Scenario& sc, Plan& plan);

// Export options as the command line gives them (shared by `export` and `plan --export`).
struct ExportArgs {
  std::vector<std::string> formats;
  std::string firmware = "px4";
  std::string vehicle = "multirotor";
  std::string end = "land";
};
void add_export_options(CLI::App& cmd, ExportArgs& a, bool formats_required);
// Writes every file of every format into dir; prints what it wrote. Returns an exit code.
int write_exports(const std::string& scenario_path, const Scenario& sc, const Plan& plan, const ExportArgs& a,
                  const std::string& dir);

// Progress on stderr, only on a terminal and only once a run has taken over a second.
class Progress {
 public:
  Progress();
  ~Progress();
  void update(const std::string& line);

 private:
  double started_s_;
  bool tty_;
  bool shown_ = false;
};

}  // namespace uavplan::cli
