#include "uavplan/coordination/spacetime/space_time_astar.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "uavplan/coordination/spacetime/space_time_moves.h"

namespace uavplan {
namespace {

std::uint64_t state_key(int v, int t) {
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(t)) << 32 | static_cast<std::uint32_t>(v);
}

}  // namespace

SpaceTimeAnswer SpaceTimeSearch::find(const SpaceTimeGraph& g, const SpaceTimeQuery& q, const StopCondition& stop) {
  SpaceTimeAnswer a;
  const std::vector<int>& h = *q.h;
  const SpaceTimeTable& forbidden = *q.forbidden;
  const SpaceTimeTable* fixed = q.fixed;
  const int goal_after =
      !q.stays ? -1 : std::max(forbidden.last_time_at(q.goal), fixed ? fixed->last_time_at(q.goal) : -1);
  if (h[q.start] < 0 || goal_after == INT_MAX || !may_be_at(q, q.start, q.start_t)) return a;
  // After the last forbidden time the table no longer changes (stays only): reaching a vertex
  // later is never better than reaching it then, so states past it are told apart by vertex
  // alone. The state space is finite and a walled-in goal is known in one sweep of the graph.
  const int last = std::max(forbidden.last_time(), fixed ? fixed->last_time() : -1);
  const int still = std::min(std::max(last, 0) + 1, SpaceTimeTable::kLastTime);
  const std::size_t f_slots =
      static_cast<std::size_t>(std::max(still, q.start_t)) + 2 * static_cast<std::size_t>(g.vertex_count) + 2;
  if (live_.size() < f_slots) {
    live_.resize(f_slots, 0);
    later_.resize(f_slots);
  }
  nodes_.clear();
  focal_.clear();
  generated_.clear(4096);
  // No path ends before the goal's last forbidden time has passed: f = max(t + h, that end), still
  // admissible and consistent, and without it an agent that must wait for its goal would search
  // every state that reaches the goal too early.
  const int earliest_end = goal_after + 1;
  const auto f_of = [&](int v, int t) { return std::max(t + h[v], earliest_end); };
  int f_min = f_of(q.start, q.start_t);
  bound_ = static_cast<int>(std::floor(q.w * f_min + kWholeNumberSlack));
  int f_top = f_min;  // highest f pushed: the buckets to empty afterwards
  first_visit(q.start, q.start_t, still);
  push({q.start, q.start_t, -1, 0, f_min, -1});
  int found = -1;
  while (!focal_.empty()) {
    if ((a.expanded & 1023u) == 0 && stop.should_stop()) break;
    const int n = pop_focal();
    const Node cur = nodes_[n];
    --live_[cur.f];
    if (cur.t >= still && generated_.get(state_key(cur.v, still)) < cur.t + 1) continue;  // reached earlier since
    if (cur.v == q.goal && cur.t > goal_after) {
      found = n;
      break;
    }
    ++a.expanded;
    if (cur.t < SpaceTimeTable::kLastTime) {
      const int t1 = cur.t + 1;
      const auto expand = [&](int v) {
        if (h[v] < 0 || !may_move(q, cur.v, v, cur.t) || !turns_within(q, cur.came_from, cur.v, v)) return;
        if (!first_visit(v, t1, still)) return;
        int meetings = cur.meetings;
        if (q.avoided) meetings += q.avoided->at(v, t1) + q.avoided->moves(cur.v, v, cur.t);
        const int f = f_of(v, t1);
        f_top = std::max(f_top, f);
        push({v, t1, n, meetings, f, v == cur.v ? cur.came_from : cur.v});
      };
      expand(cur.v);  // wait
      for (int k = g.first[cur.v]; k < g.first[cur.v + 1]; ++k) expand(g.next[k]);
    }
    while (f_min <= f_top && live_[f_min] == 0) ++f_min;
    if (f_min <= f_top) raise_bound(static_cast<int>(std::floor(q.w * f_min + kWholeNumberSlack)));
  }
  if (found >= 0) {
    a.found = true;
    a.path = path_to(found);
    a.cost = nodes_[found].t;
    a.lower_bound = std::min(f_min, a.cost);
    a.meetings = nodes_[found].meetings;
  }
  for (int f = 0; f <= f_top && f < static_cast<int>(f_slots); ++f) {
    live_[f] = 0;
    later_[f].clear();
  }
  return a;
}

// Whether (v, t) is reached for the first time. Past `still` a state is its vertex alone and an
// earlier time beats a later one (A* may reach a vertex late before it reaches it early): the
// table keeps the earliest time + 1.
bool SpaceTimeSearch::first_visit(int v, int t, int still) {
  return t < still ? generated_.insert(state_key(v, t)) : generated_.keep_least(state_key(v, still), t + 1);
}

void SpaceTimeSearch::push(const Node& node) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  const int f = node.f;
  ++live_[f];
  if (f > bound_) {
    later_[f].push_back(id);
    return;
  }
  focal_.push_back(id);
  std::push_heap(focal_.begin(), focal_.end(), [this](int a, int b) { return worse(a, b); });
}

int SpaceTimeSearch::pop_focal() {
  std::pop_heap(focal_.begin(), focal_.end(), [this](int a, int b) { return worse(a, b); });
  const int n = focal_.back();
  focal_.pop_back();
  return n;
}

// Nodes whose f the bound now covers join the focal heap.
void SpaceTimeSearch::raise_bound(int bound) {
  for (int f = bound_ + 1; f <= bound && f < static_cast<int>(later_.size()); ++f) {
    for (const int id : later_[f]) {
      focal_.push_back(id);
      std::push_heap(focal_.begin(), focal_.end(), [this](int a, int b) { return worse(a, b); });
    }
    later_[f].clear();
  }
  bound_ = std::max(bound_, bound);
}

// Heap order: fewer meetings first, then smaller f, then deeper, then older.
bool SpaceTimeSearch::worse(int a, int b) const {
  const Node& x = nodes_[a];
  const Node& y = nodes_[b];
  if (x.meetings != y.meetings) return x.meetings > y.meetings;
  if (x.f != y.f) return x.f > y.f;
  if (x.t != y.t) return x.t < y.t;
  return a > b;
}

SpaceTimePath SpaceTimeSearch::path_to(int node) const {
  SpaceTimePath p;
  for (int n = node; n >= 0; n = nodes_[n].parent) p.push_back(nodes_[n].v);
  std::reverse(p.begin(), p.end());
  return p;
}

}  // namespace uavplan
