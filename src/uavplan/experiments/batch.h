// Running a sweep's runs: each one planned and verified, in this process on a pool of threads
// (oneTBB) or, isolated, each in its own `uavplan plan` process so that even a crash is only a
// row. Runs do not share mutable state: the scenarios are loaded once and read by every thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/status.h"
#include "uavplan/core/stop.h"
#include "uavplan/experiments/sweep.h"

namespace uavplan {

// A run's status: its plan's (solved, partial, failed), or what kept it from ending in one:
// timeout (stopped at the time limit), stopped (an interrupt, or the limit while the scenario
// was loaded), error (bad parameters, a malformed problem), crashed (isolated: the process died).
enum class RunStatus { solved, partial, failed, timeout, stopped, error, crashed };
inline constexpr RunStatus kRunStatuses[] = {RunStatus::solved,  RunStatus::partial, RunStatus::failed,
                                             RunStatus::timeout, RunStatus::stopped, RunStatus::error,
                                             RunStatus::crashed};
std::string_view to_string(RunStatus s);
std::optional<RunStatus> run_status_from_string(std::string_view s);
RunStatus run_status(Status s);

// A run's outcome: its status, the plan's reason (the first unsolved UAV's; stopped for a
// timeout) and message, and the row's numbers.
struct RunOutcome {
  RunStatus status = RunStatus::error;
  Reason reason = Reason::none;
  std::string algorithm;  // the planner that planned (the scenario's own when the run names none)
  bool verified = false;  // the plan holds under the verifier (every planned UAV)
  std::size_t violations = 0;
  std::size_t uavs = 0, uavs_solved = 0;
  double length_m = std::numeric_limits<double>::quiet_NaN();       // all UAVs' routes together
  double flight_time_s = std::numeric_limits<double>::quiet_NaN();  // the last arrival
  double min_separation_m = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t expansions = 0;  // search nodes, all UAVs
  std::string message;
  // Wall-clock (not reproducible; kept out of results.csv).
  double plan_ms = 0.0, wall_ms = 0.0;
};

struct RunRecord {
  RunSpec spec;
  RunOutcome outcome;
  std::string plan_file;  // relative to the batch folder; empty when no plan was made
};

// Scenarios by path and scenario overrides, each loaded once; safe to share between threads.
class ScenarioCache {
 public:
  ScenarioCache();
  ~ScenarioCache();
  // Throws InputError when the scenario does not load with these overrides.
  // `stop` bounds the load (an elevation model read); a load it stops throws Stopped.
  std::shared_ptr<const Scenario> get(const std::string& path, const ParamSetting& scenario_overrides,
                                      const StopCondition& stop = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct BatchOptions {
  int jobs = 0;                        // threads; 0: every core
  double time_limit_s = 0.0;           // per run; 0: none
  bool isolate = false;                // each run in its own process
  std::string uavplan_exe;             // isolate: the command-line tool to run
  std::string work_dir;                // isolate: where the processes write their plans
  std::uint64_t max_memory_bytes = 0;  // per run (a planner's grids); 0: no cap
  // Once set (an interrupt), no new run starts and those under way are stopped; a run cut short
  // is not reported (a later --resume runs it again).
  const std::atomic<bool>* stop = nullptr;
};

// The environment variable that tells an isolated run its batch's process id: the run ends when
// the batch does (die_with_batch() in the command-line tool).
inline constexpr const char* kParentPidVariable = "UAVPLAN_BATCH_PID";

// One run in this process: the plan's file text goes to `plan_json` (empty when none).
RunOutcome run_in_process(const RunSpec& run, const ScenarioCache& cache, const BatchOptions& options,
                          std::string& plan_json);
// One run as `uavplan plan` in its own process (process group of its own, so a terminal's
// Ctrl-C reaches only the batch, which passes it on); killed when still going at twice the time
// limit plus 5 s, and when the batch dies.
RunOutcome run_isolated(const RunSpec& run, const ScenarioCache& cache, const BatchOptions& options,
                        std::string& plan_json);

// Runs every spec on options.jobs threads; `done` is called once per finished run, one call at a
// time, with the record and the plan's text. Runs not started or cut short because of
// options.stop are not reported.
void run_batch(const std::vector<RunSpec>& runs, const ScenarioCache& cache, const BatchOptions& options,
               const std::function<void(RunRecord&&, const std::string& plan_json)>& done);

// The plan file of a run inside the batch folder: runs/000042.plan.json.
std::string run_plan_file(std::size_t index);

}  // namespace uavplan
