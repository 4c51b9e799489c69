// uavplan plan SCENARIO: plan, verify, write DIR/plan.json, print a summary.
#include <cstdio>
#include <iostream>
#include <optional>

#include "commands.h"
#include "uavplan/experiments/plan_run.h"
#include "uavplan/io/export.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan::cli {
namespace {

struct PlanArgs {
  std::string scenario;
  std::string out_dir = "out";
  std::string algorithm;
  std::optional<std::uint64_t> seed;
  std::vector<std::string> sets;
  RunArgs run;
  bool timing = false;
  ExportArgs exp;
};

std::optional<Overrides> parse_sets(const std::vector<std::string>& sets) {
  Overrides o;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::cerr << "uavplan: --set " << s << ": expected key=value\n";
      return std::nullopt;
    }
    o.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  return o;
}

void print_summary(const Plan& plan, const std::string& path) {
  // depart_s + flight_s: the plan's clock at the last movement; a wait on the ground is before depart_s.
  std::printf("%-12s %-8s %10s %9s %9s %9s %9s %10s %10s\n", "uav", "status", "length_m", "depart_s", "flight_s",
              "arrival_s", "turn_deg", "climb_deg", "gap_m");
  for (const UavPlan& u : plan.uavs) {
    auto m = [&](const char* k) {
      const auto it = u.metrics.find(k);
      return it == u.metrics.end() ? std::string("-") : std::to_string(it->second).substr(0, 9);
    };
    std::printf("%-12s %-8s %10s %9s %9s %9s %9s %10s %10s\n", u.id.c_str(), std::string(to_string(u.status)).c_str(),
                m("length_m").c_str(), m("departure_s").c_str(), m("flight_time_s").c_str(), m("arrival_s").c_str(),
                m("max_turn_deg").c_str(), m("max_climb_deg").c_str(), m("min_gap_m").c_str());
  }
  // Why each UAV is not solved; the notes of solved ones (an anytime planner stopped with its best
  // route, a mission's counts), the first few.
  constexpr int kNotesShown = 3;
  int notes = 0;
  for (const UavPlan& u : plan.uavs)
    if (u.status != Status::solved)
      std::printf("%s: %s\n", u.id.c_str(), u.message.c_str());
    else if (!u.message.empty() && notes++ < kNotesShown)
      std::printf("%s: note: %s\n", u.id.c_str(), u.message.c_str());
  if (notes > kNotesShown) std::printf("(%d more notes in the plan file)\n", notes - kNotesShown);
  const auto sep = plan.metrics.find("min_separation_m");
  if (sep != plan.metrics.end()) std::printf("min separation between UAVs: %.3f m\n", sep->second);
  if (plan.formation && plan.formation->arrival_spread_s)
    std::printf("arrivals (each UAV at its goal to stay) within %.3f s of one another\n",
                *plan.formation->arrival_spread_s);
  const auto metric = [&](const char* k) { return plan.metrics.count(k) ? plan.metrics.at(k) : 0.0; };
  if (plan.formation)
    std::printf("in shape %.1f s (all UAVs together), %d breaks, %d reversals, backing up %.1f m\n",
                metric("time_in_shape_s"), static_cast<int>(metric("breaks")), static_cast<int>(metric("reversals")),
                metric("backing_up_m"));
  std::printf("status: %s, algorithm %s, seed %llu, %.1f ms; %s\n", std::string(to_string(plan.status)).c_str(),
              plan.algorithm.c_str(), static_cast<unsigned long long>(plan.seed), plan.plan_ms,
              path.empty() ? "nothing written (the export was refused)" : ("plan written to " + path).c_str());
}

bool interrupted_nothing_written() {
  if (!interrupted()) return false;
  std::cerr << "uavplan: interrupted; nothing written\n";
  return true;
}

// plan.json and the exports asked for, all or nothing: an export refused (a UAV that does not
// hold, an export that cannot be made) writes nothing, plan.json neither (the summary says why;
// `plan` without --export keeps the plan). Without --export the last export in the folder is
// stale and goes.
int write_outputs(const PlanArgs& a, const Scenario& sc, const Plan& plan) {
  const ExportFile plan_file{"plan.json", plan_to_json(plan, {a.timing}), ""};
  const std::string path = a.out_dir + "/plan.json";
  PreparedExport prepared;
  const int export_rc = a.exp.formats.empty() ? kExitOk : prepare_exports(a.scenario, sc, plan, a.exp, prepared);
  if (interrupted_nothing_written()) return kExitInterrupted;
  if (export_rc != kExitOk) {
    print_summary(plan, "");
    return export_rc;
  }
  ExportReplaced replaced;
  if (!a.exp.formats.empty()) {
    replaced = write_export(a.out_dir, prepared.files, {plan_file}, prepared.source);
  } else {
    StagedFiles staged(a.out_dir);
    staged.add(plan_file.name, plan_file.content);
    staged.commit();
    clear_export(a.out_dir);
  }
  print_summary(plan, path);
  if (!a.exp.formats.empty()) report_exports(a.out_dir, prepared, replaced);
  return kExitOk;
}

int run_plan(const PlanArgs& a) {
  check_output_dir(a.out_dir);
  // --time-limit counts from the process's start: loading the program and the scenario count too.
  const StopCondition stop = run_stop(a.run);
  auto overrides = parse_sets(a.sets);
  if (!overrides) return kExitBadInput;
  // --algorithm wins over the file's planner before the scenario is checked (a mission's
  // planners are checked against the one that will plan it).
  if (!a.algorithm.empty()) overrides->emplace_back("planner.algorithm", a.algorithm);
  Scenario sc;
  try {
    sc = load_scenario(a.scenario, *overrides, stop);
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const Stopped&) {  // reading an elevation model took the time left
    if (interrupted_nothing_written()) return kExitInterrupted;
    std::cerr << a.scenario << ": stopped: the time limit ran out while the scenario was loaded; nothing written\n";
    return kExitNotSolved;
  }
  for (const std::string& hint : sc.hints) std::cerr << hint << "\n";
  // An export that cannot be made is bad input now, before planning writes anything.
  if (const auto problem = export_request_problem(sc, a.exp)) {
    std::cerr << a.scenario << ": export: " << *problem << "\n";
    return kExitBadInput;
  }
  PlanRequest request;
  if (!a.algorithm.empty()) request.algorithm = a.algorithm;
  request.seed = a.seed;
  request.stop = stop;  // --time-limit counts from the process's start
  request.threads = a.run.threads;
  request.max_memory_bytes = a.run.max_memory_bytes;
  Progress progress;
  progress.update("planning");
  progress.start_heartbeat();
  request.progress = [&](std::size_t done, std::size_t total) {
    progress.update(done == total ? "verifying the plan"
                                  : "planning: " + std::to_string(done) + "/" + std::to_string(total) + " UAVs");
  };
  Plan plan;
  try {
    plan = plan_and_verify(sc, request).plan;
  } catch (const std::invalid_argument& e) {
    std::cerr << a.scenario << ": planner: " << e.what() << "\n";
    return kExitBadInput;
  }
  progress.finish();
  for (const std::string& note : plan.notes) std::cerr << a.scenario << ": note: " << note << "\n";
  if (interrupted_nothing_written()) return kExitInterrupted;
  const int export_rc = write_outputs(a, sc, plan);
  if (export_rc != kExitOk) return export_rc;
  return plan.status == Status::solved ? kExitOk : kExitNotSolved;
}

}  // namespace

void add_plan_command(CLI::App& app, std::function<int()>& run) {
  auto args = std::make_shared<PlanArgs>();
  CLI::App* cmd = app.add_subcommand("plan", "Plan a scenario, verify the plan and write DIR/plan.json");
  cmd->add_option("scenario", args->scenario, "Scenario file (YAML or JSON)")->required();
  cmd->add_option("-o,--out", args->out_dir, "Output directory (default: out)");
  cmd->add_option("--algorithm", args->algorithm, "Planner name, overriding the scenario's");
  cmd->add_option("--seed", args->seed, "Random seed, overriding the scenario's")->check(non_negative_integer());
  cmd->add_option("--set", args->sets,
                  "key=value override: a bare key sets planner.params.KEY, a dotted path (uavs[0].speed) any field");
  add_run_options(*cmd, args->run);
  cmd->add_flag("--timing", args->timing, "Also write wall-clock timing into plan.json (not byte-reproducible)");
  add_export_options(*cmd, args->exp, false);
  cmd->footer("Example: uavplan plan scenarios/demo.yaml -o out --set cell_m=4 --export qgc,geojson");
  args->run.max_memory_bytes = default_memory_cap_bytes();
  cmd->callback([args, &run] {
    run = [args] {
      install_interrupt_handlers();
      return run_plan(*args);
    };
  });
}

}  // namespace uavplan::cli
