// What a space-time search may do from a state, by its query: be at a vertex at a time, move
// (or wait) in a step, turn; shared by the time-expanded and the safe-interval search.
#pragma once

#include <vector>

#include "uavplan/coordination/spacetime/space_time_astar.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {

// Whether the agent may be at v at time t.
inline bool may_be_at(const SpaceTimeQuery& q, int v, int t) {
  return q.forbidden->at(v, t) == 0 && (!q.fixed || q.fixed->at(v, t) == 0);
}

// Whether the agent may move u -> v (u == v: wait) from time t to t + 1.
inline bool may_move(const SpaceTimeQuery& q, int u, int v, int t) {
  if (v != q.goal && v != u && q.terminals_from >= 0 && v >= q.terminals_from) return false;
  if (!may_be_at(q, v, t + 1) || q.forbidden->moves(u, v, t) > 0) return false;
  return !q.fixed || q.fixed->moves(u, v, t) == 0;
}

// Whether moving on to v, having come from `from` into u (from < 0: none yet), keeps the turn
// limit; a wait always does.
inline bool turns_within(const SpaceTimeQuery& q, int from, int u, int v) {
  if (q.position == nullptr || q.max_turn_rad >= kPi || v == u) return true;
  const std::vector<Vec3>& at = *q.position;
  const Vec3 in = from >= 0 ? Vec3(at[u] - at[from]) : q.heading;
  return in.isZero() || turn_within(in, at[v] - at[u], q.max_turn_rad);
}

}  // namespace uavplan
