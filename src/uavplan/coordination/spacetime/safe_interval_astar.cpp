#include "uavplan/coordination/spacetime/safe_interval_astar.h"

#include <algorithm>
#include <climits>
#include <stdexcept>

#include "uavplan/coordination/spacetime/space_time_moves.h"

namespace uavplan {
namespace {

constexpr int kForever = INT_MAX;

// The last time of v's safe interval that holds t (the agent at v at t, waiting step by step);
// kForever when it reaches `still`, after which the tables no longer change.
int interval_end(const SpaceTimeQuery& q, int v, int t, int still) {
  // Past v's last entry (a time it is taken or waiting there is forbidden) it is free for good:
  // most vertices, answered without a scan.
  const int taken = std::max(q.forbidden->last_time_at(v), q.fixed ? q.fixed->last_time_at(v) : -1);
  if (t > taken) return kForever;
  for (;; ++t) {
    const bool waits = may_move(q, v, v, t);
    if (t >= still) return waits ? kForever : t;
    if (!waits) return t;
  }
}

std::uint64_t interval_key(int v, int end, int still) {
  const int e = end == kForever ? still + 1 : end;
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(e)) << 32 | static_cast<std::uint32_t>(v);
}

}  // namespace

SpaceTimeAnswer SafeIntervalSearch::find(const SpaceTimeGraph& g, const SpaceTimeQuery& q, const StopCondition& stop) {
  if (q.avoided != nullptr || q.w != 1.0) throw std::invalid_argument("safe intervals take hard constraints only");
  SpaceTimeAnswer a;
  const std::vector<int>& h = *q.h;
  const int goal_after =
      !q.stays ? -1 : std::max(q.forbidden->last_time_at(q.goal), q.fixed ? q.fixed->last_time_at(q.goal) : -1);
  if (h[q.start] < 0 || goal_after == INT_MAX || !may_be_at(q, q.start, q.start_t)) return a;
  const int last = std::max(q.forbidden->last_time(), q.fixed ? q.fixed->last_time() : -1);
  const int still = std::min(std::max(last, 0) + 1, SpaceTimeTable::kLastTime);
  const int earliest_end = goal_after + 1;  // as in the time-expanded search
  nodes_.clear();
  open_.clear();
  reached_.clear(4096);
  const auto heap_order = [this](int x, int y) { return better(y, x); };
  // The earliest arrival at (v, its interval) wins; later ones are dropped.
  const auto reach = [&](int v, int t, int end, int parent, int came_from) {
    if (!reached_.keep_least(interval_key(v, end, still), t + 1)) return;
    nodes_.push_back({v, t, parent, std::max(t + h[v], earliest_end), came_from});
    open_.push_back(static_cast<int>(nodes_.size()) - 1);
    std::push_heap(open_.begin(), open_.end(), heap_order);
  };
  reach(q.start, q.start_t, interval_end(q, q.start, q.start_t, still), -1, -1);
  int found = -1;
  while (!open_.empty()) {
    if ((a.expanded & 1023u) == 0 && stop.should_stop()) break;
    std::pop_heap(open_.begin(), open_.end(), heap_order);
    const int n = open_.back();
    open_.pop_back();
    const Node cur = nodes_[n];
    const int end = interval_end(q, cur.v, cur.t, still);
    if (reached_.get(interval_key(cur.v, end, still)) < cur.t + 1) continue;  // reached earlier since
    if (cur.v == q.goal && cur.t > goal_after) {
      found = n;
      break;
    }
    ++a.expanded;
    // Leaving later than `still` is never better than leaving then.
    const int latest = std::min(end == kForever ? std::max(cur.t, still) : end, SpaceTimeTable::kLastTime - 1);
    for (int k = g.first[cur.v]; k < g.first[cur.v + 1]; ++k) {
      const int u = g.next[k];
      if (h[u] < 0 || !turns_within(q, cur.came_from, cur.v, u)) continue;
      for (int depart = cur.t; depart <= latest; ++depart) {
        if (!may_move(q, cur.v, u, depart)) continue;
        const int u_end = interval_end(q, u, depart + 1, still);
        reach(u, depart + 1, u_end, n, cur.v);
        if (u_end == kForever) break;
        depart = std::max(depart, u_end - 1);  // a later arrival within that interval is no better
      }
    }
  }
  if (found >= 0) {
    a.found = true;
    a.path = path_to(found);
    a.cost = nodes_[found].t;
    a.lower_bound = a.cost;  // the first goal state taken is the earliest (consistent bound)
  }
  return a;
}

// Heap order: smaller f first, then later arrival (deeper), then older.
bool SafeIntervalSearch::better(int a, int b) const {
  const Node& x = nodes_[a];
  const Node& y = nodes_[b];
  if (x.f != y.f) return x.f < y.f;
  if (x.t != y.t) return x.t > y.t;
  return a < b;
}

// The path from the start's time: the agent waits at each vertex until it leaves for the next.
SpaceTimePath SafeIntervalSearch::path_to(int node) const {
  std::vector<int> chain;
  for (int n = node; n >= 0; n = nodes_[n].parent) chain.push_back(n);
  std::reverse(chain.begin(), chain.end());
  SpaceTimePath p{nodes_[chain.front()].v};
  int t = nodes_[chain.front()].t;
  for (std::size_t k = 1; k < chain.size(); ++k) {
    const Node& next = nodes_[chain[k]];
    for (; t + 1 < next.t; ++t) p.push_back(p.back());
    p.push_back(next.v);
    ++t;
  }
  return p;
}

}  // namespace uavplan
