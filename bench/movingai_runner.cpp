#include "movingai_runner.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "stats.h"
#include "textbook_astar.h"
#include "uavplan/core/rng.h"
#include "uavplan/io/movingai.h"
#include "uavplan/planning/search/grid_astar.h"
#include "uavplan/planning/search/jps2d.h"
#include "uavplan/planning/search/jps3d.h"
#include "uavplan/planning/search/theta_star.h"

namespace uavplan::bench {
namespace {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - lo) * (v[hi] - v[lo]);
}

// Any-angle routes may beat the grid optimum by at most these factors (the data's README).
double any_angle_bound(bool three_d) { return three_d ? 1.128 : 1.0824; }

struct Summary {
  int problems = 0, solved = 0;
  double worst = 0.0;  // max |cost - optimal|, or for any-angle the smallest cost / optimal
  double median_ms = 0.0, p95_ms = 0.0, ref_median_ms = 0.0, exp_per_s = 0.0;
  double mean_expanded = 0.0;  // per problem
};

Summary summarise(const std::vector<const MovingAiProblemResult*>& rs, bool any_angle) {
  Summary s;
  std::vector<double> t, rt;
  double total_ms = 0.0, expanded = 0.0;
  s.worst = any_angle ? 1e300 : 0.0;
  for (const auto* r : rs) {
    ++s.problems;
    s.solved += r->within;
    if (r->solved && any_angle && r->optimal > 0.0) s.worst = std::min(s.worst, r->cost / r->optimal);
    if (r->solved && !any_angle) s.worst = std::max(s.worst, std::abs(r->cost - r->optimal));
    t.push_back(r->ms);
    rt.push_back(r->ref_ms);
    total_ms += r->ms;
    expanded += static_cast<double>(r->expanded);
  }
  if (any_angle && s.worst > 1e299) s.worst = 1.0;
  s.median_ms = percentile(t, 0.5);
  s.p95_ms = percentile(t, 0.95);
  s.ref_median_ms = percentile(rt, 0.5);
  s.exp_per_s = total_ms > 0 ? expanded / (total_ms / 1000.0) : 0.0;
  s.mean_expanded = s.problems > 0 ? expanded / s.problems : 0.0;
  return s;
}

void check_algorithm(const std::string& algorithm, bool three_d) {
  if (algorithm != "astar" && algorithm != "jps" && algorithm != "jps+" && algorithm != "jps-forward" &&
      algorithm != "theta")
    throw std::invalid_argument("unknown grid search '" + algorithm +
                                "' (expected astar, jps, jps-forward, jps+ or theta)");
  if (three_d && algorithm == "jps+")
    throw std::invalid_argument("jps+ (a jump table) is 2-D only here; use jps, astar or theta");
  if (!three_d && algorithm == "jps-forward")
    throw std::invalid_argument("jps-forward (3-D JPS from the start alone) is for a .3dmap; 2-D jps is one-way");
}

}  // namespace

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

bool MovingAiReport::passed() const {
  return std::all_of(problems.begin(), problems.end(), [](const auto& p) { return p.within; });
}

MovingAiReport run_movingai(const std::string& map_path, const std::string& scen_path, const MovingAiOptions& opt) {
  const bool one_way = opt.algorithm == "jps-forward";
  const bool jump = opt.algorithm == "jps" || opt.algorithm == "jps+" || one_way;
  MovingAiReport rep;
  rep.map = map_path;
  rep.algorithm = opt.algorithm;
  rep.reference = opt.reference;
  rep.three_d = is_movingai_3d(map_path);
  check_algorithm(opt.algorithm, rep.three_d);
  auto t0 = Clock::now();
  const BitGrid grid = rep.three_d ? read_movingai_3dmap(map_path) : read_movingai_map(map_path);
  rep.load_ms = ms_since(t0);
  rep.cells[0] = grid.nx();
  rep.cells[1] = grid.ny();
  rep.cells[2] = grid.nz();
  rep.grid_mb = static_cast<double>(grid.memory_bytes()) / (1024.0 * 1024.0);
  const auto all = rep.three_d ? read_movingai_3dscen(scen_path) : read_movingai_scen(scen_path);

  std::vector<std::size_t> pick;
  const std::size_t n = all.size();
  if (opt.limit > 0 && static_cast<std::size_t>(opt.limit) < n) {
    for (int i = 0; i < opt.limit; ++i) pick.push_back(static_cast<std::size_t>(i) * n / opt.limit);
  } else {
    for (std::size_t i = 0; i < n; ++i) pick.push_back(i);
  }

  GridAStar astar(grid, bounding_box_moves(grid), GridHeuristic::octile);
  std::unique_ptr<Jps2d> jps = jump && !rep.three_d ? std::make_unique<Jps2d>(grid) : nullptr;
  std::unique_ptr<Jps3d> jps3;
  if (jump && rep.three_d) {
    t0 = Clock::now();
    Jps3dOptions o;
    o.both_directions = !one_way;
    jps3 = std::make_unique<Jps3d>(grid, o);
    rep.preprocess_ms = ms_since(t0);
    rep.table_mb = static_cast<double>(jps3->line_bytes()) / (1024.0 * 1024.0);
  }
  if (opt.algorithm == "jps+") {
    t0 = Clock::now();
    rep.table_built = jps->precompute();
    rep.preprocess_ms = ms_since(t0);
    rep.table_mb = static_cast<double>(jps->table_bytes()) / (1024.0 * 1024.0);
  }
  LazyThetaStar theta(grid);
  const bool any_angle = opt.algorithm == "theta";
  const double bound = any_angle_bound(rep.three_d);
  for (const std::size_t i : pick) {
    const MovingAiProblem& p = all[i];
    MovingAiProblemResult r;
    r.bucket = p.bucket;
    r.optimal = p.optimal;
    const bool inside = grid.inside(p.start[0], p.start[1], p.start[2]) && grid.inside(p.goal[0], p.goal[1], p.goal[2]);
    if (inside) {
      const std::int64_t s = grid.index(p.start[0], p.start[1], p.start[2]);
      const std::int64_t g = grid.index(p.goal[0], p.goal[1], p.goal[2]);
      t0 = Clock::now();
      const GridSearchResult res = jps         ? jps->search(s, g)
                                   : jps3      ? jps3->search(s, g)
                                   : any_angle ? theta.search(s, g)
                                               : astar.search(s, g);
      r.ms = ms_since(t0);
      r.solved = res.solved();
      r.cost = res.cost;
      r.expanded = res.expanded;
      if (opt.reference) {
        t0 = Clock::now();
        const TextbookResult ref = textbook_astar(grid, s, g);
        r.ref_ms = ms_since(t0);
        (void)ref;
      }
    }
    r.within = r.solved && (any_angle ? r.cost <= p.optimal + 1e-4 && r.cost >= p.optimal / bound - 1e-4
                                      : std::abs(r.cost - p.optimal) <= 1e-4);
    rep.problems.push_back(r);
  }
  rep.peak_rss_mb = peak_rss_mb();
  return rep;
}

std::string format_movingai(const MovingAiReport& rep) {
  const bool any_angle = rep.algorithm == "theta";
  std::string out;
  char buf[320];
  std::snprintf(buf, sizeof buf, "map %s (%d x %d x %d), algorithm %s, %zu problems, load %.1f ms, grid %.2f MB\n",
                rep.map.c_str(), rep.cells[0], rep.cells[1], rep.cells[2], rep.algorithm.c_str(), rep.problems.size(),
                rep.load_ms, rep.grid_mb);
  out += buf;
  if (rep.algorithm == "jps+" && !rep.table_built) {
    std::snprintf(buf, sizeof buf, "jump table: none (the grid is more than %d cells a side): jumps scanned\n",
                  JumpTable::kMaxSide);
    out += buf;
  } else if (rep.algorithm == "jps+") {
    std::snprintf(buf, sizeof buf, "jump table: built once in %.1f ms (not in the query times), %.2f MB\n",
                  rep.preprocess_ms, rep.table_mb);
    out += buf;
  }
  if ((rep.algorithm == "jps" || rep.algorithm == "jps-forward") && rep.three_d) {
    std::snprintf(buf, sizeof buf,
                  "bit lines along x, y and z: built once in %.1f ms (not in the query times), %.2f MB\n",
                  rep.preprocess_ms, rep.table_mb);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "%-13s %8s %7s %12s %10s %10s %12s %12s %9s\n", "buckets", "problems", "solved",
                any_angle ? "min_cost/opt" : "max|c-opt|", "median_ms", "p95_ms", "expansions/s", "textbook_ms",
                "speed-up");
  out += buf;
  if (rep.problems.empty()) return out;
  int lo = rep.problems.front().bucket, hi = lo;
  for (const auto& p : rep.problems) {
    lo = std::min(lo, p.bucket);
    hi = std::max(hi, p.bucket);
  }
  const int width = std::max(1, (hi - lo + 10) / 10);
  auto row = [&](const char* label, const Summary& s) {
    if (rep.reference)
      std::snprintf(buf, sizeof buf, "%-13s %8d %7d %12.3g %10.4f %10.4f %12.3g %12.4f %8.2fx\n", label, s.problems,
                    s.solved, s.worst, s.median_ms, s.p95_ms, s.exp_per_s, s.ref_median_ms,
                    s.median_ms > 0 ? s.ref_median_ms / s.median_ms : 0.0);
    else  // not run: say so rather than print zeros
      std::snprintf(buf, sizeof buf, "%-13s %8d %7d %12.3g %10.4f %10.4f %12.3g %12s %9s\n", label, s.problems,
                    s.solved, s.worst, s.median_ms, s.p95_ms, s.exp_per_s, "not run", "-");
    out += buf;
  };
  for (int b = lo; b <= hi; b += width) {
    std::vector<const MovingAiProblemResult*> rs;
    for (const auto& p : rep.problems)
      if (p.bucket >= b && p.bucket < b + width) rs.push_back(&p);
    if (rs.empty()) continue;
    char label[32];
    std::snprintf(label, sizeof label, "%d-%d", b, b + width - 1);
    row(label, summarise(rs, any_angle));
  }
  std::vector<const MovingAiProblemResult*> all;
  for (const auto& p : rep.problems) all.push_back(&p);
  const Summary s = summarise(all, any_angle);
  row("all", s);
  if (rep.reference)
    std::snprintf(
        buf, sizeof buf,
        "summary: %d/%d within the %s, median %.4f ms against the textbook A*'s %.4f ms: %.2fx; %.1f expansions "
        "per problem; peak RSS %.1f MB\n",
        s.solved, s.problems, any_angle ? "any-angle bounds" : "optimum (1e-4)", s.median_ms, s.ref_median_ms,
        s.median_ms > 0 ? s.ref_median_ms / s.median_ms : 0.0, s.mean_expanded, rep.peak_rss_mb);
  else
    std::snprintf(buf, sizeof buf,
                  "summary: %d/%d within the %s, median %.4f ms (no textbook A* run); %.1f expansions per problem; "
                  "peak RSS %.1f MB\n",
                  s.solved, s.problems, any_angle ? "any-angle bounds" : "optimum (1e-4)", s.median_ms, s.mean_expanded,
                  rep.peak_rss_mb);
  out += buf;
  return out;
}

std::string movingai_json(const MovingAiReport& rep) {
  const bool any_angle = rep.algorithm == "theta";
  std::vector<const MovingAiProblemResult*> all;
  for (const auto& p : rep.problems) all.push_back(&p);
  const Summary s = summarise(all, any_angle);
  nlohmann::ordered_json j;
  j["map"] = rep.map;
  j["algorithm"] = rep.algorithm;
  j["cells"] = {rep.cells[0], rep.cells[1], rep.cells[2]};
  j["problems"] = s.problems;
  j["solved_within"] = s.solved;
  j[any_angle ? "min_cost_over_optimal" : "max_abs_cost_error"] = s.worst;
  j["median_ms"] = s.median_ms;
  j["p95_ms"] = s.p95_ms;
  j["expansions_per_s"] = s.exp_per_s;
  j["mean_expanded"] = s.mean_expanded;
  if (rep.reference) {  // absent when the textbook A* did not run
    j["textbook_median_ms"] = s.ref_median_ms;
    j["speedup"] = s.median_ms > 0 ? s.ref_median_ms / s.median_ms : 0.0;
  }
  j["load_ms"] = rep.load_ms;
  j["preprocess_ms"] = rep.preprocess_ms;
  j["grid_mb"] = rep.grid_mb;
  j["peak_rss_mb"] = rep.peak_rss_mb;
  j["passed"] = rep.passed();
  return j.dump(1) + "\n";
}

MemoryProbe probe_a1_memory(const std::string& path, std::int64_t blocked) {
  MemoryProbe m;
  {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f.get(), "voxel 896 390 255\n");
    Rng rng(1);
    for (std::int64_t i = 0; i < blocked; ++i)
      std::fprintf(f.get(), "%d %d %d\n", static_cast<int>(rng.uniform_int(0, 895)),
                   static_cast<int>(rng.uniform_int(0, 389)), static_cast<int>(rng.uniform_int(0, 254)));
  }
  m.blocked = blocked;
  {
    std::ifstream in(path, std::ios::ate | std::ios::binary);
    m.file_mb = static_cast<double>(in.tellg()) / (1024.0 * 1024.0);
  }
  const auto t0 = Clock::now();
  const BitGrid g = read_movingai_3dmap(path);
  m.load_ms = ms_since(t0);
  m.grid_mb = static_cast<double>(g.memory_bytes()) / (1024.0 * 1024.0);
  m.peak_rss_mb = peak_rss_mb();
  std::remove(path.c_str());
  return m;
}

}  // namespace uavplan::bench
