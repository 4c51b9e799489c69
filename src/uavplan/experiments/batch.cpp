#include "uavplan/experiments/batch.h"
#include "uavplan/core/text.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "uavplan/evaluation/verifier.h"
#include "uavplan/experiments/plan_run.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/io/scenario_io.h"

extern char** environ;

namespace uavplan {

std::string_view to_string(RunStatus s) {
  switch (s) {
    case RunStatus::solved:
      return "solved";
    case RunStatus::partial:
      return "partial";
    case RunStatus::failed:
      return "failed";
    case RunStatus::timeout:
      return "timeout";
    case RunStatus::stopped:
      return "stopped";
    case RunStatus::error:
      return "error";
    case RunStatus::crashed:
      return "crashed";
  }
  return "error";
}

std::optional<RunStatus> run_status_from_string(std::string_view s) {
  for (const RunStatus r : kRunStatuses)
    if (to_string(r) == s) return r;
  return std::nullopt;
}

RunStatus run_status(Status s) {
  switch (s) {
    case Status::solved:
      return RunStatus::solved;
    case Status::partial:
      return RunStatus::partial;
    case Status::failed:
      return RunStatus::failed;
  }
  return RunStatus::failed;
}

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

bool scenario_key(const std::string& key) { return key.find_first_of(".[") != std::string::npos; }

void split_params(const ParamSetting& all, ParamSetting& scenario_overrides, Params& planner_params) {
  for (const auto& [k, v] : all) {
    if (scenario_key(k))
      scenario_overrides.emplace_back(k, v);
    else
      planner_params[k] = v;
  }
}

// The row's numbers from a finalized plan and its violations.
RunOutcome outcome_of(const Plan& plan, std::size_t violations, bool time_limited) {
  RunOutcome o;
  o.status = run_status(plan.status);
  o.reason = plan.reason;
  o.algorithm = plan.algorithm;
  o.violations = violations;
  o.verified = violations == 0;
  o.uavs = plan.uavs.size();
  double last = -1.0;
  for (const UavPlan& u : plan.uavs) {
    o.uavs_solved += u.status == Status::solved;
    o.expansions += u.stats.nodes_expanded;
    if (!u.trajectory.empty()) last = std::max(last, u.trajectory.back().t_s);
    if (time_limited && u.reason == Reason::stopped) o.status = RunStatus::timeout;
  }
  if (last >= 0.0) o.flight_time_s = last;
  if (const auto it = plan.metrics.find("total_length_m"); it != plan.metrics.end()) o.length_m = it->second;
  if (const auto it = plan.metrics.find("min_separation_m"); it != plan.metrics.end()) o.min_separation_m = it->second;
  if (plan.status != Status::solved) {
    o.message = plan.message;
    for (const UavPlan& u : plan.uavs)
      if (o.message.empty() && u.status != Status::solved) o.message = u.id + ": " + u.message;
  }
  return o;
}

std::string first_line(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  return s.size() > 500 ? s.substr(0, 500) : s;
}

}  // namespace

struct ScenarioCache::Impl {
  mutable std::mutex mutex;
  mutable std::map<std::string, std::shared_ptr<const Scenario>> loaded;
};

ScenarioCache::ScenarioCache() : impl_(std::make_unique<Impl>()) {}
ScenarioCache::~ScenarioCache() = default;

std::shared_ptr<const Scenario> ScenarioCache::get(const std::string& path, const ParamSetting& overrides,
                                                   const StopCondition& stop) const {
  const std::string key = path + '\n' + params_text(overrides);
  {
    std::lock_guard lock(impl_->mutex);
    if (const auto it = impl_->loaded.find(key); it != impl_->loaded.end()) return it->second;
  }
  // Loaded outside the lock (two threads may both load the first time; one copy is kept).
  auto sc = std::make_shared<const Scenario>(load_scenario(path, Overrides(overrides.begin(), overrides.end()), stop));
  std::lock_guard lock(impl_->mutex);
  return impl_->loaded.emplace(key, std::move(sc)).first->second;
}

std::string run_plan_file(std::size_t index) { return strf("runs/%06zu.plan.json", index); }

RunOutcome run_in_process(const RunSpec& run, const ScenarioCache& cache, const BatchOptions& options,
                          std::string& plan_json) {
  const double time_limit_s = options.time_limit_s;
  const auto t0 = Clock::now();
  plan_json.clear();
  RunOutcome o;
  ParamSetting overrides;
  PlanRequest request;
  split_params(run.params, overrides, request.params);
  if (!run.planner.empty()) request.algorithm = run.planner;
  request.seed = run.seed;
  request.time_limit_s = time_limit_s;
  if (options.stop) request.stop = StopCondition::cancel_flag(options.stop);  // an interrupt stops the run
  request.threads = 1;                                                        // the batch is parallel; a run is not
  request.max_memory_bytes = options.max_memory_bytes;
  try {
    // The load counts against the run's limits as the plan does.
    const StopCondition load_stop =
        (time_limit_s > 0.0 ? request.stop | StopCondition::time_limit(time_limit_s) : request.stop)
            .with_threads(1)
            .with_memory_cap(options.max_memory_bytes);
    const auto sc = cache.get(run.scenario, overrides, load_stop);
    const VerifiedPlan v = plan_and_verify(*sc, request);
    o = outcome_of(v.plan, v.violations.size(), time_limit_s > 0.0);
    o.plan_ms = v.plan_ms;
    plan_json = plan_to_json(v.plan);
  } catch (const std::exception& e) {
    o = RunOutcome{};
    o.status = RunStatus::error;
    o.reason = Reason::invalid;
    o.message = first_line(e.what());
  } catch (const Stopped&) {  // while the scenario was loaded (an elevation model read)
    o = RunOutcome{};
    o.status = RunStatus::stopped;
    o.reason = Reason::stopped;
    o.message = "stopped while the scenario was loaded";
  }
  o.wall_ms = ms_since(t0);
  return o;
}

namespace {

// `uavplan plan` of one run into `dir`, one thread, with the run's seed, planner, parameters,
// time limit and memory cap.
std::vector<std::string> isolated_args(const RunSpec& run, const BatchOptions& options, const fs::path& dir) {
  std::vector<std::string> args = {
      options.uavplan_exe,      "plan",      run.scenario, "-o",      dir.string(), "--seed",
      std::to_string(run.seed), "--threads", "1",          "--timing"};
  if (!run.planner.empty()) args.insert(args.end(), {"--algorithm", run.planner});
  for (const auto& [k, v] : run.params) args.insert(args.end(), {"--set", std::string(k).append("=").append(v)});
  if (options.time_limit_s > 0.0) {
    const std::string limit = strf("%.17g", options.time_limit_s);  // exactly the sweep's (1e-7 is not "0.000000")
    args.insert(args.end(), {"--time-limit", limit});
  }
  args.insert(args.end(), {"--max-memory", std::to_string(options.max_memory_bytes)});
  return args;
}

// The process in its own process group, stdin and stdout /dev/null, stderr to a fresh
// `err_path` (never through a link planted under its name). The child ends with the batch: it is
// told its parent, and dies when that is gone (a killed batch leaves no orphans to race a later
// --resume). -1 when it cannot start.
pid_t spawn_run(std::vector<std::string> args, const std::string& err_path) {
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  ::unlink(err_path.c_str());
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, kParentPidVariable, std::strlen(kParentPidVariable)) != 0) env_text.emplace_back(*e);
  env_text.push_back(std::string(kParentPidVariable) + "=" + std::to_string(::getpid()));
  std::vector<char*> envp;
  envp.reserve(env_text.size() + 1);
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, args.front().c_str(), &actions, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return spawned == 0 ? pid : -1;
}

// Waits for the run's process: an interrupt is passed on as SIGINT to its process group (the
// terminal's Ctrl-C does not reach it); past twice the time limit plus 5 s it is killed.
struct Waited {
  int wstatus = 0;
  bool killed = false;
};
Waited wait_run(pid_t pid, const BatchOptions& options, Clock::time_point t0) {
  const double kill_after_ms = options.time_limit_s > 0.0 ? 2000.0 * options.time_limit_s + 5000.0 : -1.0;
  Waited w;
  bool interrupted = false;
  while (::waitpid(pid, &w.wstatus, WNOHANG) == 0) {
    if (options.stop && options.stop->load() && !interrupted) {
      ::kill(-pid, SIGINT);
      interrupted = true;
    }
    if (kill_after_ms > 0.0 && !w.killed && ms_since(t0) > kill_after_ms) {
      ::kill(pid, SIGKILL);
      w.killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return w;
}

// The outcome of a plan the process wrote, verified here against the run's scenario.
RunOutcome read_isolated_plan(const RunSpec& run, const ScenarioCache& cache, const BatchOptions& options,
                              const fs::path& plan_path, std::string& plan_json) {
  RunOutcome o;
  try {
    ParamSetting overrides;
    Params unused;
    split_params(run.params, overrides, unused);
    const auto sc = cache.get(run.scenario, overrides);
    const std::string text = read_text_file(plan_path.string());
    Plan plan = parse_plan(text, plan_path.string());
    o = outcome_of(plan, verify_plan(*sc, plan).size(), options.time_limit_s > 0.0);
    o.plan_ms = plan.plan_ms;
    plan_json = plan_to_json(plan);  // without the timing the process wrote
  } catch (const std::exception& e) {
    o.status = RunStatus::error;
    o.reason = Reason::invalid;
    o.message = first_line(e.what());
  }
  return o;
}

}  // namespace

RunOutcome run_isolated(const RunSpec& run, const ScenarioCache& cache, const BatchOptions& options,
                        std::string& plan_json) {
  const auto t0 = Clock::now();
  plan_json.clear();
  const fs::path dir = fs::path(options.work_dir) / ("run-" + std::to_string(run.index));
  fs::create_directories(dir);
  const std::string err_path = (dir / "stderr.txt").string();
  const pid_t pid = spawn_run(isolated_args(run, options, dir), err_path);
  RunOutcome o;
  if (pid < 0) {
    o.message = "could not start " + options.uavplan_exe;
    o.wall_ms = ms_since(t0);
    return o;
  }
  const Waited w = wait_run(pid, options, t0);
  std::string err;
  try {
    err = read_text_file(err_path);
  } catch (const std::exception&) {
  }
  const fs::path plan_path = dir / "plan.json";
  if (w.killed) {
    o.status = RunStatus::timeout;
    o.reason = Reason::stopped;
    o.message = "killed at twice the time limit plus 5 s";
  } else if (WIFSIGNALED(w.wstatus)) {
    o.status = RunStatus::crashed;
    o.message = "the run's process died of signal " + std::to_string(WTERMSIG(w.wstatus));
  } else if (WIFEXITED(w.wstatus) && (WEXITSTATUS(w.wstatus) == 0 || WEXITSTATUS(w.wstatus) == 1) &&
             fs::exists(plan_path)) {
    o = read_isolated_plan(run, cache, options, plan_path, plan_json);
  } else {
    o.status = RunStatus::error;
    o.reason = Reason::invalid;
    o.message =
        first_line(err.empty() ? "the run's process ended with exit " + std::to_string(WEXITSTATUS(w.wstatus)) : err);
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  o.wall_ms = ms_since(t0);
  return o;
}

void run_batch(const std::vector<RunSpec>& runs, const ScenarioCache& cache, const BatchOptions& options,
               const std::function<void(RunRecord&&, const std::string& plan_json)>& done) {
  std::mutex done_mutex;
  const int jobs = options.jobs > 0 ? options.jobs : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(jobs);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, runs.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            if (options.stop && options.stop->load()) return;
            std::string json;
            RunRecord rec;
            rec.spec = runs[i];
            rec.outcome = options.isolate ? run_isolated(runs[i], cache, options, json)
                                          : run_in_process(runs[i], cache, options, json);
            if (options.stop && options.stop->load()) return;  // cut short: not a result; --resume runs it again
            if (!json.empty()) rec.plan_file = run_plan_file(runs[i].index);
            std::lock_guard lock(done_mutex);
            done(std::move(rec), json);
          }
        },
        tbb::simple_partitioner());
  });
}

}  // namespace uavplan
