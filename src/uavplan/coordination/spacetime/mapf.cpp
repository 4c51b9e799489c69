#include "uavplan/coordination/spacetime/mapf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "uavplan/coordination/spacetime/cbs.h"
#include "uavplan/coordination/spacetime/mapf_conflicts.h"
#include "uavplan/coordination/spacetime/prioritized.h"

namespace uavplan {

std::string mapf_problem_mistake(const MapfProblem& p) {
  if (p.starts.size() != p.goals.size()) return "as many goals as starts expected";
  // Each agent's distances to its goal: one int per vertex per agent.
  const std::uint64_t table_bytes = sizeof(int) * static_cast<std::uint64_t>(p.starts.size()) *
                                    static_cast<std::uint64_t>(std::max(p.graph.vertex_count, 0));
  if (table_bytes > kMostDistanceTableBytes)
    return std::to_string(p.starts.size()) + " agents on " + std::to_string(p.graph.vertex_count) + " cells need " +
           std::to_string(table_bytes >> 20) + " MiB of distance tables, more than " +
           std::to_string(kMostDistanceTableBytes >> 20) + " MiB";
  const auto off = [&](int v) { return v < 0 || v >= p.graph.vertex_count; };
  std::unordered_set<int> starts, goals;
  for (std::size_t i = 0; i < p.starts.size(); ++i) {
    const std::string who = "agent " + std::to_string(i);
    if (off(p.starts[i]) || off(p.goals[i])) return who + ": start or goal off the graph";
    if (!starts.insert(p.starts[i]).second) return who + ": its start is another agent's start";
    if (!goals.insert(p.goals[i]).second) return who + ": its goal is another agent's goal";
  }
  return "";
}

namespace {

// Grid MAPF as a space-time model: one search per agent to its goal, vertex and swap conflicts.
class GridModel final : public SpaceTimeModel {
 public:
  GridModel(const MapfProblem& p, const std::vector<std::vector<int>>& h) : p_(p), h_(h) {}
  int agent_count() const override { return static_cast<int>(p_.starts.size()); }
  int vertex_count() const override { return p_.graph.vertex_count; }
  SpaceTimeAnswer plan(int i, const SpaceTimeTable& forbidden, const SpaceTimeTable* avoided, double w,
                       SpaceTimeSearches& search, const StopCondition& stop) const override {
    const SpaceTimeQuery q{p_.starts[i], p_.goals[i], &h_[i], &forbidden, avoided, w};
    return search.expanded.find(p_.graph, q, stop);
  }
  int lone_cost(int i) const override { return h_[i][p_.starts[i]]; }
  void add_path(int /*agent*/, const SpaceTimePath& path, SpaceTimeTable& table) const override {
    table.add_path(path);
  }
  std::optional<PathConflict> first_conflict(const std::vector<SpaceTimePath>& paths) const override {
    const std::optional<MapfConflict> c = uavplan::first_conflict(paths, p_.graph.vertex_count);
    if (!c) return std::nullopt;
    if (c->swap()) return PathConflict{{c->a, c->v, c->u, c->t}, {c->b, c->u, c->v, c->t}};  // a: v -> u, b: u -> v
    return PathConflict{{c->a, c->v, -1, c->t}, {c->b, c->v, -1, c->t}};
  }
  int count_conflicts(const std::vector<SpaceTimePath>& paths) const override {
    return uavplan::count_conflicts(paths, p_.graph.vertex_count);
  }

 private:
  const MapfProblem& p_;
  const std::vector<std::vector<int>>& h_;
};

void finish(MapfResult& r) {
  if (!r.solved()) return;
  r.sum_of_costs = sum_of_costs(r.paths);
  r.makespan = makespan(r.paths);
}

// ECBS first, which proves its bound, with three quarters of the time left (all of it without a
// time limit); where it finds nothing in that, prioritised planning with the rest: a solution
// without a proven bound, said so in its method.
MapfResult solve_automatic(const SpaceTimeModel& model, const MapfOptions& o) {
  constexpr double kBoundedShare = 0.75;
  const StopCondition first =
      o.stop.has_time_limit() ? o.stop | StopCondition::time_limit(kBoundedShare * o.stop.seconds_left()) : o.stop;
  MapfResult bounded = solve_cbs(model, o.w, first);
  if (bounded.solved() || o.stop.should_stop()) return bounded;
  MapfResult quick = solve_prioritized(model, o.orders, o.stop);
  quick.low_level_expansions += bounded.low_level_expansions;
  quick.high_level_nodes = bounded.high_level_nodes;
  quick.lower_bound = bounded.lower_bound;
  if (quick.solved()) quick.method += " after ECBS " + bounded.message + " (no bound proven)";
  return quick;
}

}  // namespace

MapfResult solve_mapf(const MapfProblem& problem, const MapfOptions& o) {
  if (const std::string m = mapf_problem_mistake(problem); !m.empty()) throw std::invalid_argument(m);
  if (!(o.w >= 1.0) || !std::isfinite(o.w)) throw std::invalid_argument("w must be 1 or more");
  if (o.orders < 1) throw std::invalid_argument("orders must be 1 or more");
  std::vector<std::vector<int>> h;
  int lone_sum = 0;
  for (std::size_t i = 0; i < problem.starts.size(); ++i) {
    if (o.stop.should_stop()) {  // a table is a search of the whole graph: large maps take a while
      MapfResult r;
      r.fail(Reason::stopped, "stopped (" + std::to_string(i) + " of " + std::to_string(problem.starts.size()) +
                                  " agents' distance tables built)");
      return r;
    }
    h.push_back(distances_to(problem.graph, problem.goals[i]));
    const int d = h.back()[problem.starts[i]];
    if (d < 0) {
      MapfResult r;
      r.fail(Reason::no_route, "agent " + std::to_string(i) + " cannot reach its goal");
      return r;
    }
    lone_sum += d;
  }
  MapfResult r = solve_space_time(GridModel(problem, h), o);
  r.lower_bound = std::max(r.lower_bound, lone_sum);
  return r;
}

MapfResult solve_space_time(const SpaceTimeModel& model, const MapfOptions& o) {
  MapfResult r;
  switch (o.method) {
    case MapfMethod::prioritized:
      r = solve_prioritized(model, o.orders, o.stop);
      break;
    case MapfMethod::cbs:
      r = solve_cbs(model, 1.0, o.stop);
      break;
    case MapfMethod::ecbs:
      r = solve_cbs(model, o.w, o.stop);
      break;
    case MapfMethod::automatic:
      r = solve_automatic(model, o);
      break;
  }
  finish(r);
  return r;
}

const char* to_string(MapfMethod m) {
  switch (m) {
    case MapfMethod::automatic:
      return "auto";
    case MapfMethod::prioritized:
      return "prioritized";
    case MapfMethod::ecbs:
      return "ecbs";
    case MapfMethod::cbs:
      return "cbs";
  }
  return "?";
}

bool parse_mapf_method(const std::string& word, MapfMethod& out) {
  for (const MapfMethod m : {MapfMethod::automatic, MapfMethod::prioritized, MapfMethod::ecbs, MapfMethod::cbs})
    if (word == to_string(m)) {
      out = m;
      return true;
    }
  return false;
}

}  // namespace uavplan
