// The command-line tool: one small file per subcommand. Exit codes: 0 solved / plan holds,
// 1 not solved / violations, 2 bad input, 3 output not written, 130 interrupted.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/stop.h"
#include "uavplan/experiments/plan_run.h"
#include "uavplan/io/export.h"
#include "uavplan/io/flight_schedule.h"

namespace uavplan::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitNotSolved = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitOutputError = 3;  // the output could not be written (a full disk, permissions)

// Each registers its subcommand on the app and sets `run` to the action to take when chosen.
void add_plan_command(CLI::App& app, std::function<int()>& run);
void add_verify_command(CLI::App& app, std::function<int()>& run);
void add_info_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);
void add_export_command(CLI::App& app, std::function<int()>& run);
void add_report_command(CLI::App& app, std::function<int()>& run);
void add_batch_command(CLI::App& app, std::function<int()>& run);
void add_fly_command(CLI::App& app, std::function<int()>& run);

// Loads both and checks that every plan UAV is in the scenario; on bad input prints the one-line
// error on stderr and returns false (the caller exits with kExitBadInput).
bool load_scenario_and_plan(const std::string& scenario_path, const std::string& plan_path, Scenario& sc, Plan& plan);
// The same for a second plan of a scenario already loaded (a flight beside its plan).
bool load_plan_of(const Scenario& sc, const std::string& scenario_path, const std::string& plan_path, Plan& plan);

// Export options as the command line gives them (shared by `export` and `plan --export`).
struct ExportArgs {
  std::vector<std::string> formats;
  std::string firmware = "px4";
  std::string vehicle;  // empty: fixedwing for a formation_mission (its runway), else multirotor
  std::string end = "land";
  std::string fence = "bounds";
  std::string altitude;                                      // empty: amsl over an elevation model, else home
  double flat_altitude_m = ExportOptions{}.flat_altitude_m;  // a flat world's plan flies this high
  int max_items = 0;                                         // 0: what the firmware stores
  bool force = false;                                        // write the UAVs that hold when others do not
  bool options_given = false;  // --firmware, --vehicle, --end, --fence or --force on the command line
};
void add_export_options(CLI::App& cmd, ExportArgs& a, bool formats_required);
// The library's options for what the command line asked.
ExportOptions export_options_of(const Scenario& sc, const ExportArgs& a);
// Why the export asked for cannot be made (checked before anything is planned or written).
std::optional<std::string> export_request_problem(const Scenario& sc, const ExportArgs& a);
// Verifies the plan with the legs the mission files add (flight_export.h); when every UAV holds
// (or --force and some do) builds every file of every format into `out`; else prints why and
// builds nothing. Returns an exit code (1: refused, 2: an export that cannot be made).
struct PreparedExport {
  std::vector<ExportFile> files;
  std::vector<std::string> notes, left_out;
  std::string source;                    // the fingerprint of the scenario, the plan and the options (export.h)
  VerifiedExport flights;                // what the files fly
  std::vector<ScheduledStart> schedule;  // when each mission starts (autopilot formats: schedule.json)
};
int prepare_exports(const std::string& scenario_path, const Scenario& sc, const Plan& plan, const ExportArgs& a,
                    PreparedExport& out);
// Prints what was written (and for which UAV, where the file name does not say), what the folder
// kept of an earlier export of the same plan and removed of the last one, and the notes.
void report_exports(const std::string& dir, const PreparedExport& done, const ExportReplaced& replaced);

// Limits every planning command takes: --time-limit, --threads, --max-memory.
struct RunArgs {
  double time_limit_s = 0.0;
  int threads = 0;
  std::uint64_t max_memory_bytes = 0;  // set to the default when the options are added
};

// Validators with one-line messages.
CLI::Validator positive_number();
CLI::Validator non_negative_integer();
void add_run_options(CLI::App& cmd, RunArgs& a);
// Interrupts: the first SIGINT / SIGTERM stops planning (the command ends with exit 130).
void install_interrupt_handlers();
// In a run a batch started in its own process: end with the batch (a killed batch leaves no orphans).
void die_with_batch();
bool interrupted();
const std::atomic<bool>* interrupt_flag();
inline constexpr int kExitInterrupted = 130;
// The stop condition of a run: the interrupt, the time limit, threads and memory.
StopCondition run_stop(const RunArgs& a);

// Makes everything printed on stdout and stderr (C and C++ streams) terminal-safe: control
// characters from names and messages are written as escapes (terminal.cpp). Call first in main.
void install_terminal_filter();

// Progress on stderr, only on a terminal and only once a run has taken over a second.
// One line of progress on stderr when it is a terminal, shown once a run has taken a second.
// Thread-safe; with the heartbeat on, the last line is shown again every half second with the
// seconds elapsed, so that a long step that reports nothing itself still shows it is working.
class Progress {
 public:
  Progress();
  ~Progress();
  void update(const std::string& line);
  void start_heartbeat();
  // Ends the line (and the heartbeat) before results are printed; later updates show nothing.
  void finish();

 private:
  void show(const std::string& line);

  double started_s_;
  bool tty_;
  bool shown_ = false;
  std::mutex mutex_;
  std::condition_variable_any beat_cv_;
  std::string last_;
  std::jthread beat_;
};

}  // namespace uavplan::cli
