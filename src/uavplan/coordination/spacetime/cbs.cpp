#include "uavplan/coordination/spacetime/cbs.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>
#include <utility>

#include "uavplan/coordination/spacetime/space_time_astar.h"

namespace uavplan {
namespace {

// A path's cost: the time it reaches its goal.
int path_cost(const SpaceTimePath& p) { return static_cast<int>(p.size()) - 1; }

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
  ConflictSearch(const SpaceTimeModel& m, double w, const StopCondition& stop, std::uint64_t most_nodes)
      : m_(m), w_(w), stop_(stop), most_nodes_(most_nodes), n_(m.agent_count()) {}

  MapfResult run();

 private:
  bool plan_root();
  void paths_of(int node, std::vector<SpaceTimePath>& paths, std::vector<int>& bounds) const;
  void add_child(int parent, std::vector<SpaceTimePath>& paths, const std::vector<int>& bounds, const AgentStep& step);
  void open(int node);
  int take();

  const SpaceTimeModel& m_;
  double w_;
  const StopCondition& stop_;
  std::uint64_t most_nodes_;
  int n_;
  std::vector<HighNode> nodes_;
  std::vector<SpaceTimePath> root_paths_;
  std::vector<int> root_bounds_;
  std::set<std::pair<int, int>> by_bound_, by_cost_;  // open nodes: (bound, id), (cost, id)
  std::set<std::tuple<int, int, int>> focal_;         // (conflicts, cost, id), cost <= w * least bound
  int focal_cost_ = -1;
  SpaceTimeSearches search_;
  SpaceTimeTable forbidden_, avoided_;
  std::uint64_t expanded_ = 0;
};

// Each agent alone under no constraint, avoiding the paths of those planned before it.
bool ConflictSearch::plan_root() {
  HighNode root;
  avoided_.clear(m_.vertex_count(), static_cast<std::size_t>(n_) * 64);
  forbidden_.clear(m_.vertex_count());
  for (int i = 0; i < n_; ++i) {
    SpaceTimeAnswer a = m_.plan(i, forbidden_, &avoided_, w_, search_, stop_);
    expanded_ += a.expanded;
    if (!a.found) return false;
    m_.add_path(i, a.path, avoided_);
    root.cost += a.cost;
    root.bound += a.lower_bound;
    root_bounds_.push_back(a.lower_bound);
    root_paths_.push_back(std::move(a.path));
  }
  root.conflicts = m_.count_conflicts(root_paths_);
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
void ConflictSearch::add_child(int parent, std::vector<SpaceTimePath>& paths, const std::vector<int>& bounds,
                               const AgentStep& step) {
  const int agent = step.agent;
  forbidden_.clear(m_.vertex_count());
  const auto forbid = [&](int cv, int cu, int ct) {
    if (cu < 0)
      forbidden_.add_vertex(cv, ct);
    else
      forbidden_.add_move(cv, cu, ct);
  };
  forbid(step.v, step.u, step.t);
  for (int k = parent; k > 0; k = nodes_[k].parent)
    if (nodes_[k].agent == agent) forbid(nodes_[k].v, nodes_[k].u, nodes_[k].t);
  avoided_.clear(m_.vertex_count(), static_cast<std::size_t>(n_) * 64);
  for (int i = 0; i < n_; ++i)
    if (i != agent) m_.add_path(i, paths[i], avoided_);
  SpaceTimeAnswer a = m_.plan(agent, forbidden_, &avoided_, w_, search_, stop_);
  expanded_ += a.expanded;
  if (!a.found) return;  // this branch has no solution (or the stop came)
  HighNode c;
  c.parent = parent;
  c.agent = agent;
  c.v = step.v;
  c.u = step.u;
  c.t = step.t;
  c.agent_bound = std::max(bounds[agent], a.lower_bound);
  c.cost = nodes_[parent].cost - path_cost(paths[agent]) + a.cost;
  c.bound = nodes_[parent].bound - bounds[agent] + c.agent_bound;
  std::swap(paths[agent], a.path);  // the child's paths, counted in place of a copy of them all
  c.conflicts = m_.count_conflicts(paths);
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
  const int most = static_cast<int>(std::floor(w_ * by_bound_.begin()->first + kWholeNumberSlack));
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
  while (rooted && !by_bound_.empty() && !stop_.should_stop() &&
         (most_nodes_ == 0 || r.high_level_nodes < most_nodes_)) {
    r.lower_bound = by_bound_.begin()->first;
    const int id = take();
    ++r.high_level_nodes;
    paths_of(id, paths, bounds);
    const std::optional<PathConflict> c = m_.first_conflict(paths);
    if (!c) {
      r.succeed();
      r.paths = std::move(paths);
      break;
    }
    add_child(id, paths, bounds, c->a);
    add_child(id, paths, bounds, c->b);
  }
  r.low_level_expansions = expanded_;
  if (!r.solved()) {
    if (stop_.should_stop())
      r.fail(Reason::stopped, "stopped");
    else if (!rooted)
      r.fail(Reason::no_route, "an agent cannot reach its goal");
    else if (by_bound_.empty())
      r.fail(Reason::conflict, "no solution: every branch of constraints is closed");
    else
      r.fail(Reason::budget, "no solution within " + std::to_string(most_nodes_) + " high-level nodes");
  }
  return r;
}

}  // namespace

MapfResult solve_cbs(const SpaceTimeModel& model, double w, const StopCondition& stop, std::uint64_t most_nodes) {
  ConflictSearch search(model, w, stop, most_nodes);
  MapfResult r = search.run();
  const std::string name = strf("ecbs w=%g", w);
  r.method = w > 1.0 ? name : "cbs";
  return r;
}

}  // namespace uavplan
