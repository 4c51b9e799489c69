#include "mapf_runner.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "stats.h"
#include "uavplan/coordination/spacetime/mapf_conflicts.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/mapf_file.h"

namespace uavplan::bench {
namespace {

namespace fs = std::filesystem;

// An instance file and its agent count; the instance itself is read when it is run, so that a
// folder of many instances never sits in memory at once.
struct Listed {
  std::string file;
  std::size_t agents = 0;
};

struct Loaded {
  MapfInstance instance;
  MapfProblem problem;  // instance.problem(), checked
};

Loaded load_instance(const std::string& path) {
  Loaded l{read_mapf_instance(path), {}};
  l.problem = l.instance.problem();
  if (const std::string m = mapf_problem_mistake(l.problem); !m.empty()) throw InputError(path, 0, "", m);
  return l;
}

// Names with their numbers compared as numbers: ex2 before ex10.
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      const std::string x = a.substr(i, ie - i), y = b.substr(j, je - j);
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// Instance files sorted by agent count, then by name (natural_less), each count thinned to
// `limit` spread evenly.
std::vector<Listed> list_instances(const std::string& dir, int limit) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir, 0, "", "not a folder of instance files");
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".yaml" && e.is_regular_file(ec)) files.push_back(e.path().filename().string());
  if (files.empty()) throw InputError(dir, 0, "", "no .yaml instance files");
  std::vector<Listed> all;
  for (const std::string& f : files)  // every file checked before any is run
    all.push_back({f, load_instance((fs::path(dir) / f).string()).instance.names.size()});
  std::sort(all.begin(), all.end(), [&](const Listed& a, const Listed& b) {
    return a.agents != b.agents ? a.agents < b.agents : natural_less(a.file, b.file);
  });
  if (limit <= 0) return all;
  std::vector<Listed> kept;
  for (std::size_t first = 0; first < all.size();) {
    std::size_t end = first;
    while (end < all.size() && all[end].agents == all[first].agents) ++end;
    const std::size_t n = end - first, take = std::min(n, static_cast<std::size_t>(limit));
    for (std::size_t k = 0; k < take; ++k) kept.push_back(std::move(all[first + k * n / take]));
    first = end;
  }
  return kept;
}

// libMultiRobotPlanning's ECBS (w = 1.3) and CBS on these instances, measured on this machine
// (../shared/data/README.md): agents -> {solved share, median ms, worst ms}; < 0 not given.
struct Anchor {
  double ecbs_solved, ecbs_median_ms, ecbs_worst_ms;
  const char* cbs;
};
const std::map<int, Anchor>& anchors() {
  static const std::map<int, Anchor> a = [] {
    std::map<int, Anchor> m;
    for (int agents = 10; agents <= 100; agents += 10) m[agents] = {1.0, -1.0, -1.0, "n.g."};  // ECBS: 100 % at all
    m[10] = {1.0, 1.2, -1.0, "10/10"};
    m[30].cbs = "6/10";
    m[40].cbs = "0/7";
    m[50].ecbs_median_ms = 36.0;
    m[100] = {1.0, 270.0, 1060.0, "n.g."};
    return m;
  }();
  return a;
}

std::string cell_ms(double ms) {
  char s[32];
  if (ms < 0.0) return "";
  std::snprintf(s, sizeof s, ms < 10.0 ? "%.2f" : ms < 100.0 ? "%.1f" : "%.0f", ms);
  return s;
}

}  // namespace

double MapfRun::ratio() const {
  const int best = optimum >= 0 ? optimum : lower_bound;
  return best > 0 ? static_cast<double>(sum_of_costs) / best : 1.0;
}

bool MapfBenchReport::passed() const {
  return std::all_of(runs.begin(), runs.end(), [](const MapfRun& r) { return r.solved && r.invalid.empty(); });
}

MapfBenchReport run_mapf_bench(const std::string& dir, const MapfBenchOptions& o,
                               const std::function<void(std::size_t, std::size_t)>& progress) {
  if (!o.out_dir.empty()) {
    check_output_dir(o.out_dir, "--out");
    std::error_code ec;
    if (fs::equivalent(o.out_dir, dir, ec))  // a solution is named after its instance
      throw InputError(o.out_dir, 0, "--out", "the instance folder itself: the solutions would replace the instances");
  }
  const std::vector<Listed> instances = list_instances(dir, o.limit);
  MapfBenchReport report;
  report.options = o;
  std::vector<std::pair<std::string, std::string>> files;
  for (std::size_t k = 0; k < instances.size(); ++k) {
    if (o.solver.stop.should_stop()) break;
    const Loaded loaded = load_instance((fs::path(dir) / instances[k].file).string());
    const MapfInstance& in = loaded.instance;
    const MapfProblem& problem = loaded.problem;
    MapfOptions solver = o.solver;
    solver.stop = solver.stop | StopCondition::time_limit(o.time_limit_s);
    const auto t0 = std::chrono::steady_clock::now();
    const MapfResult r = solve_mapf(problem, solver);
    MapfRun run;
    run.ms = ms_since(t0);
    run.file = instances[k].file;
    run.agents = static_cast<int>(in.names.size());
    run.solved = r.solved();
    run.method = r.solved() ? r.method : r.message;
    run.sum_of_costs = r.sum_of_costs;
    run.lower_bound = r.lower_bound;
    if (r.solved()) {
      if (const auto why = mapf_solution_problem(problem.graph, problem.starts, problem.goals, r.paths))
        run.invalid = *why;
      files.emplace_back(run.file, mapf_solution_yaml(in, r, run.ms / 1000.0));
    }
    if (o.optimal_limit_s > 0.0) {
      MapfOptions optimal = o.solver;
      optimal.method = MapfMethod::cbs;
      optimal.stop = o.solver.stop | StopCondition::time_limit(o.optimal_limit_s);
      const MapfResult best = solve_mapf(problem, optimal);
      if (best.solved()) run.optimum = best.sum_of_costs;
      run.lower_bound = std::max(run.lower_bound, best.lower_bound);
    }
    report.runs.push_back(std::move(run));
    if (progress) progress(k + 1, instances.size());
  }
  if (!o.out_dir.empty() && !o.solver.stop.should_stop()) {  // interrupted: nothing written
    StagedFiles staged(o.out_dir);
    for (const auto& [name, content] : files) staged.add(name, content);
    staged.commit();
  }
  return report;
}

std::string format_mapf_bench(const MapfBenchReport& rep) {
  std::string out;
  char line[512];
  const MapfOptions& s = rep.options.solver;
  std::snprintf(line, sizeof line,
                "grid MAPF (4-connected, waits, vertex + swap conflicts, sum of costs); ours: %s (w = %g, %d "
                "orders), %.0f s per instance; every solution checked by our validator\n",
                to_string(s.method), s.w, s.orders, rep.options.time_limit_s);
  out += line;
  out += rep.options.optimal_limit_s > 0.0
             ? "SOC/best: over CBS's optimum where it finished within " + cell_ms(rep.options.optimal_limit_s * 1e3) +
                   " ms, else over the best lower bound known\n"
             : "SOC/best: over the best lower bound known (lone shortest paths; --optimal-limit adds CBS's optimum)\n";
  std::snprintf(line, sizeof line, "%6s %5s | %7s %9s %9s %9s %8s %13s %6s %6s %7s | %23s %6s\n", "agents", "inst",
                "solved", "median ms", "p95 ms", "worst ms", "SOC mean", "SOC/best mean", "max", "by PP", "our CBS",
                "ECBS-1.3 solved/med/max", "CBS");
  out += line;
  for (std::size_t first = 0; first < rep.runs.size();) {
    std::size_t end = first;
    while (end < rep.runs.size() && rep.runs[end].agents == rep.runs[first].agents) ++end;
    std::vector<double> ms;
    double soc = 0.0, worst_ratio = 0.0, ratio_sum = 0.0;
    int solved = 0, prioritized = 0, optima = 0;
    for (std::size_t k = first; k < end; ++k) {
      const MapfRun& r = rep.runs[k];
      ms.push_back(r.ms);  // an unsolved instance counts at its time (the limit)
      if (!r.solved || !r.invalid.empty()) continue;
      ++solved;
      soc += r.sum_of_costs;
      worst_ratio = std::max(worst_ratio, r.ratio());
      ratio_sum += r.ratio();
      prioritized += r.method.rfind("prioritized", 0) == 0 ? 1 : 0;
      optima += r.optimum >= 0 ? 1 : 0;
    }
    const int agents = rep.runs[first].agents;
    const auto anchor = anchors().find(agents);
    std::string ref;
    if (anchor != anchors().end()) {
      const Anchor& a = anchor->second;
      const auto given = [](double v) { return v < 0.0 ? std::string("n.g.") : cell_ms(v); };
      ref = (a.ecbs_solved >= 1.0 ? "100%" : "") + std::string(" / ") + given(a.ecbs_median_ms) + " / " +
            given(a.ecbs_worst_ms);
    }
    const std::string ours =
        rep.options.optimal_limit_s > 0.0 ? std::to_string(optima) + "/" + std::to_string(end - first) : "";
    std::snprintf(line, sizeof line, "%6d %5zu | %6.0f%% %9s %9s %9s %8.1f %13.3f %6.3f %6d %7s | %23s %6s\n", agents,
                  end - first, 100.0 * solved / static_cast<double>(end - first), cell_ms(median(ms)).c_str(),
                  cell_ms(percentile(ms, 95)).c_str(), cell_ms(*std::max_element(ms.begin(), ms.end())).c_str(),
                  solved ? soc / solved : 0.0, solved ? ratio_sum / solved : 0.0, worst_ratio, prioritized,
                  ours.c_str(), ref.c_str(), anchor != anchors().end() ? anchor->second.cbs : "");
    out += line;
    first = end;
  }
  out += "reference: libMultiRobotPlanning measured on this machine (../shared/data/README.md); n.g.: not given\n";
  for (const MapfRun& r : rep.runs)
    if (!r.invalid.empty()) out += "INVALID " + printable(r.file) + ": " + r.invalid + "\n";
  for (const MapfRun& r : rep.runs)
    if (!r.solved) out += "unsolved " + printable(r.file) + ": " + r.method + "\n";
  return out;
}

}  // namespace uavplan::bench
