// uavplan batch SWEEP -o DIR: every run of a sweep planned and verified, on every core (oneTBB)
// and, with --mpi under mpirun, across machines; DIR/results.csv, timings.csv, each run's plan,
// a summary table. A batch killed part way continues with --resume.
//
// DIR/journal/ (experiments/journal.h) holds one line per finished run: a SIGKILL loses at most
// the runs under way. Under MPI every rank appends to its own journal, so DIR must be a folder
// every rank sees (as a cluster's shared file system is).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>

#include "batch_mpi.h"
#include "commands.h"
#include "uavplan/core/text.h"
#include "uavplan/experiments/batch.h"
#include "uavplan/experiments/journal.h"
#include "uavplan/experiments/ompl_log.h"
#include "uavplan/experiments/results.h"
#include "uavplan/experiments/sweep.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"

namespace uavplan::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct BatchArgs {
  std::string sweep;
  std::string out_dir;
  int jobs = 0;
  bool resume = false, dry_run = false, isolate = false, mpi = false;
  std::string ompl_log;
  std::uint64_t max_memory_bytes = 0;
};

std::string format_eta(double s) {
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%dh%02dm", int(s / 3600), int(s / 60) % 60);
  else
    std::snprintf(buf, sizeof buf, "%dm%02ds", int(s / 60), int(s) % 60);
  return buf;
}

std::string now_text() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", std::localtime(&t));
  return buf;
}

std::string host_name() {
  char buf[256] = {0};
  return ::gethostname(buf, sizeof buf - 1) == 0 ? std::string(buf) : std::string("unknown");
}

void write_ompl_logs(const BatchArgs& a, const Sweep& sweep, const std::vector<RunRecord>& all,
                     const std::string& started) {
  // One experiment per scenario: one file for one scenario, FILE-<scenario stem>.log for several.
  const std::vector<std::string>& scenarios = sweep.scenarios;
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    std::vector<RunRecord> mine;
    for (const RunRecord& r : all)
      if (r.spec.scenario == scenarios[i]) mine.push_back(r);
    std::sort(mine.begin(), mine.end(),
              [](const RunRecord& x, const RunRecord& y) { return x.spec.index < y.spec.index; });
    OmplLogHeader h;
    h.experiment = sweep.name + (scenarios.size() > 1 ? "-" + fs::path(scenarios[i]).stem().string() : "");
    h.host = host_name();
    h.date = started;
    h.setup = "sweep " + sweep.source + "\nscenario " + scenarios[i] + "\n";
    h.time_limit_s = sweep.time_limit_s;
    h.memory_limit_mb = double(a.max_memory_bytes) / (1024.0 * 1024.0);
    fs::path file = a.ompl_log;
    if (scenarios.size() > 1)
      file = file.parent_path() /
             (file.stem().string() + "-" + std::to_string(i) + "-" + fs::path(scenarios[i]).stem().string() +
              (file.extension().empty() ? ".log" : file.extension().string()));
    write_file_atomic(file.string(), ompl_log(mine, h));
    std::cout << "wrote " << file.string() << "\n";
  }
}

// The sweep and its runs; nullopt after saying why (bad input).
struct Loaded {
  Sweep sweep;
  std::vector<RunSpec> runs;
};
std::optional<Loaded> load(const BatchArgs& a, const MpiSession& mpi) {
  Loaded l;
  try {
    l.sweep = load_sweep(a.sweep);
    check_sweep(l.sweep);
    // A dry run counts the runs without listing them (a sweep may have 1e8).
    if (!a.dry_run) l.runs = expand_runs(l.sweep);
  } catch (const InputError& e) {
    if (mpi.root()) std::cerr << e.what() << "\n";
    return std::nullopt;
  }
  return l;
}

void print_dry_run(const Sweep& sweep) {
  std::size_t settings = 0;
  for (const auto& p : sweep.planners) settings += grid_size(p.params);
  std::printf("%zu runs: %zu scenarios x %zu planner settings x %zu parameter settings x %zu seeds\n", run_count(sweep),
              sweep.scenarios.size(), settings, grid_size(sweep.params), sweep.seeds.size());
}

// The runs done before (a resumed batch): rank 0 checks the journal against the sweep and merges
// it into one file, then every rank reads it. nullopt after saying why.
std::optional<std::vector<RunRecord>> previous_runs(const BatchArgs& a, const std::vector<RunSpec>& runs,
                                                    MpiSession& mpi) {
  std::vector<RunRecord> previous;
  if (mpi.root()) {
    std::string error;
    const auto kept = resumed_runs(a.out_dir, runs, error);
    if (!kept) {
      std::cerr << a.sweep << ": --resume: " << error << "\n";
      mpi.any(true);
      return std::nullopt;
    }
    previous = *kept;
    merge_journal(a.out_dir, previous);
  }
  if (mpi.any(false)) return std::nullopt;
  mpi.barrier();
  if (!mpi.root()) previous = read_journals(a.out_dir);
  return previous;
}

BatchOptions batch_options(const BatchArgs& a, const Sweep& sweep, int rank) {
  BatchOptions opt;
  opt.jobs = a.jobs;
  opt.time_limit_s = sweep.time_limit_s;
  opt.isolate = a.isolate;
  opt.uavplan_exe = fs::canonical("/proc/self/exe").string();
  opt.work_dir = (fs::path(a.out_dir) / "tmp" / ("rank-" + std::to_string(rank))).string();
  opt.max_memory_bytes = a.max_memory_bytes;
  opt.stop = interrupt_flag();
  return opt;
}

// This rank's runs on every core: each run's plan file, then its journal line; progress on
// stderr.
std::vector<RunRecord> run_pending(const BatchArgs& a, const std::vector<RunSpec>& pending, const BatchOptions& opt,
                                   JournalWriter& journal) {
  const auto t0 = Clock::now();
  ScenarioCache cache;
  std::vector<RunRecord> mine;
  Progress progress;
  const std::size_t total = pending.size();
  run_batch(pending, cache, opt, [&](RunRecord&& rec, const std::string& plan_json) {
    if (!plan_json.empty()) write_file_atomic_in((fs::path(a.out_dir) / rec.plan_file).string(), plan_json);
    journal.append(rec);
    mine.push_back(std::move(rec));
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    const double rate = double(mine.size()) / std::max(s, 1e-9);
    const std::string buf = strf("batch: %zu/%zu runs (%.0f %%), %.1f runs/s, ETA %s", mine.size(), total,
                                 100.0 * double(mine.size()) / double(std::max<std::size_t>(total, 1)), rate,
                                 format_eta(double(total - mine.size()) / std::max(rate, 1e-9)).c_str());
    progress.update(buf);
  });
  return mine;
}

// Rank 0: results.csv, timings.csv, the summary, the OMPL logs. The exit code.
int write_results(const BatchArgs& a, const Loaded& l, const std::vector<RunRecord>& all, std::size_t before,
                  double total_s, const std::string& started, const MpiSession& mpi, int jobs, bool stopped) {
  write_file_atomic((fs::path(a.out_dir) / "results.csv").string(), results_csv(all));
  write_file_atomic((fs::path(a.out_dir) / "timings.csv").string(), timings_csv(all));
  std::cout << summary_table(all);
  std::size_t solved = 0;
  for (const RunRecord& r : all) solved += r.outcome.status == RunStatus::solved;
  std::printf(
      "%zu of %zu runs done (%zu this time, %.1f s, %d rank%s x %d jobs), %zu solved; results in %s/results.csv\n",
      all.size(), l.runs.size(), all.size() - before, total_s, mpi.size(), mpi.size() > 1 ? "s" : "",
      jobs > 0 ? jobs : int(std::max(1u, std::thread::hardware_concurrency())), solved, a.out_dir.c_str());
  if (!a.ompl_log.empty()) write_ompl_logs(a, l.sweep, all, started);
  if (stopped && all.size() < l.runs.size()) {
    std::cerr << "uavplan: interrupted after the runs under way; --resume continues the " << l.runs.size() - all.size()
              << " runs left\n";
    return kExitInterrupted;
  }
  return kExitOk;
}

int run_batch_command(const BatchArgs& a) {
  check_output_dir(a.out_dir);
  MpiSession mpi(a.mpi);
  const std::optional<Loaded> l = load(a, mpi);
  if (!l) return kExitBadInput;
  if (a.dry_run) {
    if (mpi.root()) print_dry_run(l->sweep);
    return kExitOk;
  }
  if (fs::exists(journal_dir(a.out_dir)) && !a.resume) {
    if (mpi.root())
      std::cerr << a.sweep << ": " << a.out_dir
                << " holds a batch already: --resume continues it, or choose another folder\n";
    return kExitBadInput;
  }
  mpi.barrier();  // every rank has looked before rank 0 touches the folder
  const std::optional<std::vector<RunRecord>> previous = previous_runs(a, l->runs, mpi);
  if (!previous) return kExitBadInput;
  const std::vector<RunSpec> pending = pending_runs(l->runs, *previous, mpi.rank(), mpi.size());
  std::optional<JournalWriter> journal;
  try {
    journal.emplace(a.out_dir, mpi.rank());
  } catch (const std::runtime_error& e) {
    std::cerr << a.out_dir << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  const fs::path runs_dir = fs::path(a.out_dir) / "runs";
  fs::create_directories(runs_dir);
  if (mpi.root()) remove_temporaries(runs_dir.string());  // plan files a killed batch was writing
  const std::string started = now_text();
  const auto t0 = Clock::now();
  install_interrupt_handlers();
  const BatchOptions opt = batch_options(a, l->sweep, mpi.rank());
  const std::vector<RunRecord> mine = run_pending(a, pending, opt, *journal);
  journal.reset();
  std::error_code ec;
  fs::remove_all(opt.work_dir, ec);
  const double total_s = std::chrono::duration<double>(Clock::now() - t0).count();

  // Rank 0 gathers every rank's runs (as journal lines) and writes the results.
  std::string lines;
  for (const RunRecord& r : mine) lines += journal_line(r) + "\n";
  const std::string gathered = mpi.gather(lines);
  const bool stopped = mpi.any(interrupted());
  if (!mpi.root()) return stopped ? kExitInterrupted : kExitOk;
  std::vector<RunRecord> all = *previous;
  for (RunRecord& r : parse_journal_lines(gathered)) all.push_back(std::move(r));
  return write_results(a, *l, all, previous->size(), total_s, started, mpi, opt.jobs, stopped);
}

}  // namespace

void add_batch_command(CLI::App& app, std::function<int()>& run) {
  auto args = std::make_shared<BatchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "batch", "Run a sweep (scenarios x planners x parameters x seeds), each run planned and verified");
  cmd->add_option("sweep", args->sweep, "Sweep file (YAML: scenarios, planners, seeds, params, time_limit_s)")
      ->required();
  cmd->add_option("-o,--out", args->out_dir, "Output folder: results.csv, timings.csv, runs/, journal/")->required();
  cmd->add_option("--jobs", args->jobs, "Runs at once (default 0: every core)")->check(non_negative_integer());
  cmd->add_flag("--resume", args->resume, "Continue a batch that was stopped or killed, in the same folder");
  cmd->add_flag("--dry-run", args->dry_run, "Print the number of runs and exit");
  cmd->add_flag("--isolate", args->isolate, "Each run in its own process: a crash is a row, not the end of the batch");
  cmd->add_flag("--mpi", args->mpi, "Split the runs over the ranks of mpirun; rank 0 writes the results");
  cmd->add_option("--ompl-log", args->ompl_log, "Also write OMPL's benchmark log (Planner Arena); one per scenario");
  cmd->add_option("--max-memory", args->max_memory_bytes,
                  "Memory one run's planner grids may take, e.g. 2G (default: half the machine's RAM over the jobs)")
      ->transform(CLI::AsSizeValue(false));
  cmd->footer("Example: uavplan batch sweeps/compare.yaml -o results --jobs 2 --ompl-log results/ompl.log");
  cmd->callback([args, &run] {
    run = [args] {
      if (args->max_memory_bytes == 0) args->max_memory_bytes = default_run_memory_cap_bytes(args->jobs);
      return run_batch_command(*args);
    };
  });
}

}  // namespace uavplan::cli
