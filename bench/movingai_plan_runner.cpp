#include "movingai_plan_runner.h"

#include <cstdio>
#include <filesystem>

#include "stats.h"
#include "uavplan/core/text.h"
#include "uavplan/experiments/plan_run.h"
#include "uavplan/io/files.h"
#include "uavplan/io/movingai.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan::bench {
namespace {

Vec3 cell_centre(const int c[3], bool three_d) { return {c[0] + 0.5, c[1] + 0.5, three_d ? c[2] + 0.5 : 0.0}; }

MovingAiPlanRow::Run plan_one(const Scenario& sc, bool jump_points, double optimal) {
  PlanRequest req;
  req.threads = 1;
  req.params["jump_points"] = jump_points ? "true" : "false";
  const Clock::time_point t0 = Clock::now();
  const VerifiedPlan vp = plan_and_verify(sc, req);
  MovingAiPlanRow::Run run;
  run.total_ms = ms_since(t0);
  run.plan_ms = vp.plan_ms;
  const UavPlan& u = vp.plan.uavs.at(0);
  run.solved = u.solved();
  run.verified = vp.violations.empty();
  run.length_m = u.route_length_m;
  run.grid_m = u.stats.grid_route_m;
  run.expanded = u.stats.nodes_expanded;
  constexpr double kSlack = 1e-4;  // the files' optima are printed to about this
  const double straight = (*sc.uavs[0].goal - sc.uavs[0].start).norm();
  // A leg that is clear straight is flown straight, without a grid search.
  run.optimal = std::abs(run.grid_m - optimal) <= kSlack * std::max(1.0, optimal) ||
                (std::abs(run.grid_m - straight) <= kSlack && straight < optimal);
  run.within = run.length_m <= run.grid_m + kSlack && run.length_m >= straight - kSlack;
  return run;
}

}  // namespace

bool MovingAiPlanReport::passed() const {
  for (const MovingAiPlanRow& r : rows) {
    if (!r.jps.passed()) return false;
    if (astar_too && !r.astar.passed()) return false;
  }
  return true;
}

MovingAiPlanReport run_movingai_plan(const std::string& map_path, const std::string& scen_path,
                                     const MovingAiPlanOptions& opt) {
  MovingAiPlanReport rep;
  rep.map = std::filesystem::path(map_path).filename().string();
  rep.astar_too = opt.astar_too;
  const bool three_d = is_movingai_3d(map_path);
  const BitGrid grid = three_d ? read_movingai_3dmap(map_path) : read_movingai_map(map_path);
  const std::vector<MovingAiProblem> all = three_d ? read_movingai_3dscen(scen_path) : read_movingai_scen(scen_path);
  rep.cells[0] = grid.nx();
  rep.cells[1] = grid.ny();
  rep.cells[2] = grid.nz();
  for (std::int64_t i = 0; i < grid.size(); ++i) rep.blocked += grid.blocked(i);
  const std::vector<CellBox> boxes = merge_blocked_cells(grid);
  rep.boxes = boxes.size();
  std::vector<MovingAiProblem> problems;
  for (const MovingAiProblem& p : all)
    if (std::isfinite(p.optimal)) problems.push_back(p);
  if (opt.limit > 0 && static_cast<std::size_t>(opt.limit) < problems.size()) {
    std::vector<MovingAiProblem> pick;
    for (int i = 0; i < opt.limit; ++i)
      pick.push_back(problems[static_cast<std::size_t>(i) * problems.size() / opt.limit]);
    problems.swap(pick);
  }
  if (problems.empty()) return rep;

  // The user's view: the scenario as a file is read by the scenario reader, then planned.
  const std::string yaml = movingai_scenario_yaml(grid, boxes, rep.map, problems[0]);
  rep.yaml_kb = static_cast<double>(yaml.size()) / 1024.0;
  if (!opt.scenario_out.empty()) write_file_atomic(opt.scenario_out, yaml);
  Clock::time_point t0 = Clock::now();
  Scenario sc = parse_scenario(yaml, rep.map);
  rep.load_ms = ms_since(t0);
  for (std::size_t n = 0; n < problems.size(); ++n) {
    const MovingAiProblem& p = problems[n];
    sc.uavs[0].start = cell_centre(p.start, three_d);
    sc.uavs[0].goal = cell_centre(p.goal, three_d);
    MovingAiPlanRow row;
    row.optimal = p.optimal;
    row.jps = plan_one(sc, true, p.optimal);
    if (n == 0) rep.first_plan_ms = row.jps.total_ms;
    if (opt.astar_too) row.astar = plan_one(sc, false, p.optimal);
    for (const auto* run : {&row.jps, &row.astar}) {
      if (run == &row.astar && !opt.astar_too) continue;
      if (run->passed()) continue;
      rep.misses.push_back(
          strf("%s from (%d, %d, %d) to (%d, %d, %d): %s, %s, grid route %.6f against the optimum "
               "%.6f, flown %.6f",
               run == &row.jps ? "JPS" : "A*", p.start[0], p.start[1], p.start[2], p.goal[0], p.goal[1], p.goal[2],
               run->solved ? "solved" : "not solved", run->verified ? "verified" : "REJECTED by the verifier",
               run->grid_m, p.optimal, run->length_m));
    }
    rep.rows.push_back(row);
  }
  return rep;
}

std::string format_movingai_plan(const MovingAiPlanReport& rep) {
  std::string out = strf(
      "`plan` on a MovingAI map made a scenario: %s, %d x %d x %d cells, %lld blocked as %zu boxes\n"
      "scenario %.0f KB of YAML, read in %.0f ms; the first problem planned and verified in %.0f ms\n"
      "(a one-problem `uavplan plan` spends about the two); each row: astar, cell_m 1, one thread,\n"
      "plan_and_verify (the library's plan, then the verifier), %zu problems\n\n",
      rep.map.c_str(), rep.cells[0], rep.cells[1], rep.cells[2], static_cast<long long>(rep.blocked), rep.boxes,
      rep.yaml_kb, rep.load_ms, rep.first_plan_ms, rep.rows.size());
  out +=
      "| search | solved | verified | grid route = optimum | route within | plan ms median | plan ms p95 | plan ms max "
      "| "
      "plan+verify ms p95 | expansions median |\n|---|---|---|---|---|---|---|---|---|---|\n";
  const auto line = [&](const char* name, MovingAiPlanRow::Run MovingAiPlanRow::*which) {
    std::vector<double> plan, total, expanded;
    int solved = 0, verified = 0, optimal = 0, within = 0;
    for (const MovingAiPlanRow& r : rep.rows) {
      const MovingAiPlanRow::Run& x = r.*which;
      solved += x.solved;
      verified += x.verified;
      optimal += x.optimal;
      within += x.within;
      plan.push_back(x.plan_ms);
      total.push_back(x.total_ms);
      expanded.push_back(static_cast<double>(x.expanded));
    }
    const double worst = plan.empty() ? 0.0 : *std::max_element(plan.begin(), plan.end());
    out += strf("| %s | %d | %d | %d | %d | %.1f | %.1f | %.1f | %.1f | %.0f |\n", name, solved, verified, optimal,
                within, bench::median(plan), bench::percentile(plan, 95.0), worst, bench::percentile(total, 95.0),
                bench::median(expanded));
  };
  line("JPS (astar's default here)", &MovingAiPlanRow::jps);
  if (rep.astar_too) line("A* (jump_points = false)", &MovingAiPlanRow::astar);
  for (const std::string& m : rep.misses) out += "MISS " + m + "\n";
  out +=
      "\ngrid route = optimum: the grid search's route (before shortcuts) is the file's optimum to 1e-4\n"
      "(or the straight line where it is clear: then no search): the voxelised world is the map.\n"
      "route within: the planned route is no longer than that and no shorter than the straight line\n"
      "(shortcuts are checked against the boxes, not the grid: they may cut past its corner rule).\n";
  return out;
}

}  // namespace uavplan::bench
