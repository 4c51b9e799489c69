// Safe-interval path planning (Phillips and Likhachev 2011) on unit time steps: a state is a
// vertex and one of its safe intervals (the times it may be there and wait, between the table's
// entries), reached at its earliest time; from it the agent may leave at any time of the interval,
// and each neighbour's safe interval it can reach is one successor, at the earliest arrival. The
// shortest path that keeps off the tables (query.forbidden and query.fixed), as the time-expanded
// search (space_time_astar.h) finds it, from far fewer states where agents wait: prioritised
// planning's low level. Hard constraints only (no `avoided`, w = 1).
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/coordination/spacetime/flat_counts.h"
#include "uavplan/coordination/spacetime/space_time_astar.h"

namespace uavplan {

class SafeIntervalSearch {
 public:
  // query.avoided must be null and query.w 1 (std::invalid_argument otherwise).
  SpaceTimeAnswer find(const SpaceTimeGraph& g, const SpaceTimeQuery& q, const StopCondition& stop);

 private:
  struct Node {
    int v, t, parent, f;
    int came_from;  // the vertex its last move left (-1: none yet)
  };
  bool better(int a, int b) const;
  SpaceTimePath path_to(int node) const;

  std::vector<Node> nodes_;
  std::vector<int> open_;  // heap of node indices
  FlatCounts reached_;     // (vertex, interval end) -> earliest arrival + 1
};

}  // namespace uavplan
