#include "uavplan/coordination/spacetime/cbs.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>
#include <utility>

#include "uavplan/coordination/spacetime/mapf_conflicts.h"
#include "uavplan/coordination/spacetime/space_time_astar.h"

namespace uavplan {
namespace {

// A high-level node: its parent, the agent it planned again under one more constraint (the
// root: every agent), that agent's new path and bound; the rest is the parent's.
struct HighNode {
  int parent = -1;
  int agent = -1;
  int v = 0, u = -1, t = 0;  // the constraint: agent not at v at t (u < 0), or not moving v -> u in step t
  SpaceTimePath path;
  int agent_bound = 0;
  int cost = 0, bound = 0, conflicts = 0;
};

class ConflictSearch {
 public:
  ConflictSearch(const MapfProblem& p, const std::vector<std::vector<int>>& h, double w, const StopCondition& stop)
      : p_(p), h_(h), w_(w), stop_(stop), n_(static_cast<int>(p.starts.size())) {}

  MapfResult run();

 private:
  bool plan_root();
  void paths_of(int node, std::vector<SpaceTimePath>& paths, std::vector<int>& bounds) const;
  void add_child(int parent, std::vector<SpaceTimePath>& paths, const std::vector<int>& bounds, int agent, int v, int u,
                 int t);
  void open(int node);
  int take();

  const MapfProblem& p_;
  const std::vector<std::vector<int>>& h_;
  double w_;
  const StopCondition& stop_;
  int n_;
  std::vector<HighNode> nodes_;
  std::vector<SpaceTimePath> root_paths_;
  std::vector<int> root_bounds_;
  std::set<std::pair<int, int>> by_bound_, by_cost_;  // open nodes: (bound, id), (cost, id)
  std::set<std::tuple<int, int, int>> focal_;         // (conflicts, cost, id), cost <= w * least bound
  int focal_cost_ = -1;
  SpaceTimeSearch search_;
  SpaceTimeTable forbidden_, avoided_;
  std::uint64_t expanded_ = 0;
};

// Each agent alone under no constraint, avoiding the paths of those planned before it.
bool ConflictSearch::plan_root() {
  HighNode root;
  avoided_.clear(p_.graph.vertex_count, static_cast<std::size_t>(n_) * 64);
  forbidden_.clear(p_.graph.vertex_count);
  for (int i = 0; i < n_; ++i) {
    const SpaceTimeQuery q{p_.starts[i], p_.goals[i], &h_[i], &forbidden_, &avoided_, w_};
    SpaceTimeAnswer a = search_.find(p_.graph, q, stop_);
    expanded_ += a.expanded;
    if (!a.found) return false;
    avoided_.add_path(a.path);
    root.cost += a.cost;
    root.bound += a.lower_bound;
    root_bounds_.push_back(a.lower_bound);
    root_paths_.push_back(std::move(a.path));
  }
  root.conflicts = count_conflicts(root_paths_, p_.graph.vertex_count);
  nodes_.push_back(std::move(root));
  open(0);
  return true;
}

// The node's paths and agent bounds: the newest along its chain of ancestors, else the root's.
void ConflictSearch::paths_of(int node, std::vector<SpaceTimePath>& paths, std::vector<int>& bounds) const {
  paths = root_paths_;
  bounds = root_bounds_;
  std::vector<char> seen(static_cast<std::size_t>(n_), 0);
  for (int k = node; k > 0; k = nodes_[k].parent) {
    const HighNode& h = nodes_[k];
    if (seen[h.agent]) continue;
    seen[h.agent] = 1;
    paths[h.agent] = h.path;
    bounds[h.agent] = h.agent_bound;
  }
}

// The parent's node with `agent` planned again under its constraints and the new one.
void ConflictSearch::add_child(int parent, std::vector<SpaceTimePath>& paths, const std::vector<int>& bounds, int agent,
                               int v, int u, int t) {
  forbidden_.clear(p_.graph.vertex_count);
  const auto forbid = [&](int cv, int cu, int ct) {
    if (cu < 0)
      forbidden_.add_vertex(cv, ct);
    else
      forbidden_.add_move(cv, cu, ct);
  };
  forbid(v, u, t);
  for (int k = parent; k > 0; k = nodes_[k].parent)
    if (nodes_[k].agent == agent) forbid(nodes_[k].v, nodes_[k].u, nodes_[k].t);
  avoided_.clear(p_.graph.vertex_count, static_cast<std::size_t>(n_) * 64);
  for (int i = 0; i < n_; ++i)
    if (i != agent) avoided_.add_path(paths[i]);
  const SpaceTimeQuery q{p_.starts[agent], p_.goals[agent], &h_[agent], &forbidden_, &avoided_, w_};
  SpaceTimeAnswer a = search_.find(p_.graph, q, stop_);
  expanded_ += a.expanded;
  if (!a.found) return;  // this branch has no solution (or the stop came)
  HighNode c;
  c.parent = parent;
  c.agent = agent;
  c.v = v;
  c.u = u;
  c.t = t;
  c.agent_bound = std::max(bounds[agent], a.lower_bound);
  c.cost = nodes_[parent].cost - (static_cast<int>(paths[agent].size()) - 1) + a.cost;
  c.bound = nodes_[parent].bound - bounds[agent] + c.agent_bound;
  std::swap(paths[agent], a.path);  // the child's paths, counted in place of a copy of them all
  c.conflicts = count_conflicts(paths, p_.graph.vertex_count);
  std::swap(paths[agent], a.path);
  c.path = std::move(a.path);
  nodes_.push_back(std::move(c));
  open(static_cast<int>(nodes_.size()) - 1);
}

void ConflictSearch::open(int id) {
  const HighNode& h = nodes_[id];
  by_bound_.emplace(h.bound, id);
  by_cost_.emplace(h.cost, id);
  if (h.cost <= focal_cost_) focal_.emplace(h.conflicts, h.cost, id);
}

// The open node with the fewest conflicts among those within w of the least bound.
int ConflictSearch::take() {
  const int most = static_cast<int>(std::floor(w_ * by_bound_.begin()->first + 1e-9));
  if (most > focal_cost_) {
    for (auto it = by_cost_.upper_bound({focal_cost_, INT_MAX}); it != by_cost_.end() && it->first <= most; ++it)
      focal_.emplace(nodes_[it->second].conflicts, it->first, it->second);
    focal_cost_ = most;
  }
  const int id = std::get<2>(*focal_.begin());
  focal_.erase(focal_.begin());
  by_bound_.erase({nodes_[id].bound, id});
  by_cost_.erase({nodes_[id].cost, id});
  return id;
}

MapfResult ConflictSearch::run() {
  MapfResult r;
  const bool rooted = plan_root();
  std::vector<SpaceTimePath> paths;
  std::vector<int> bounds;
  while (rooted && !by_bound_.empty() && !stop_.should_stop()) {
    r.lower_bound = by_bound_.begin()->first;
    const int id = take();
    ++r.high_level_nodes;
    paths_of(id, paths, bounds);
    const std::optional<MapfConflict> c = first_conflict(paths, p_.graph.vertex_count);
    if (!c) {
      r.solved = true;
      r.paths = std::move(paths);
      break;
    }
    if (c->swap()) {  // a moves v -> u, b moves u -> v in step t
      add_child(id, paths, bounds, c->a, c->v, c->u, c->t);
      add_child(id, paths, bounds, c->b, c->u, c->v, c->t);
    } else {
      add_child(id, paths, bounds, c->a, c->v, -1, c->t);
      add_child(id, paths, bounds, c->b, c->v, -1, c->t);
    }
  }
  r.low_level_expansions = expanded_;
  if (!r.solved)
    r.why = stop_.should_stop() ? "stopped"
            : rooted            ? "no solution: every branch of constraints is closed"
                                : "an agent cannot reach its goal";
  return r;
}

}  // namespace

MapfResult solve_cbs(const MapfProblem& problem, const std::vector<std::vector<int>>& lone_h, double w,
                     const StopCondition& stop) {
  ConflictSearch search(problem, lone_h, w, stop);
  MapfResult r = search.run();
  char name[32];
  std::snprintf(name, sizeof name, "ecbs w=%g", w);
  r.method = w > 1.0 ? name : "cbs";
  return r;
}

}  // namespace uavplan
