// One agent's shortest path in space and time (unit moves and waits) that keeps off what a
// table forbids and, among paths within a factor `w` of the shortest, meets the fewest entries
// of a second table: focal search (Pearl and Kim 1982) as ECBS's low level (Barer et al. 2014);
// w = 1 is A* with the fewest meetings among the shortest (CBS, prioritised planning).
//
// Every move and wait costs one step, so a state (vertex, time) has one cost, its time: each is
// generated once. Open nodes are kept in buckets of f = t + h (whole numbers); those with
// f <= w * f_min are in the focal heap, ordered by meetings, then f, then deeper first, then age.
// Buffers are kept between queries (no allocation per node once warm).
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/coordination/spacetime/flat_counts.h"
#include "uavplan/coordination/spacetime/space_time_graph.h"
#include "uavplan/coordination/spacetime/space_time_table.h"
#include "uavplan/core/stop.h"
#include "uavplan/core/units.h"
#include "uavplan/core/vec.h"

namespace uavplan {

struct SpaceTimeQuery {
  int start = 0, goal = 0;
  const std::vector<int>* h = nullptr;        // moves to the goal from each vertex (distances_to)
  const SpaceTimeTable* forbidden = nullptr;  // never met
  const SpaceTimeTable* avoided = nullptr;    // met as seldom as the bound allows; may be null
  double w = 1.0;                             // the path is at most w times the shortest
  int start_t = 0;                            // the time it is at `start`
  bool stays = true;                      // it stays at the goal for ever (else it only has to reach it: a via point)
  const SpaceTimeTable* fixed = nullptr;  // never met either, the same for every agent; may be null
  // Vertices from this one on are entered only as the goal (other agents' own points); -1: all.
  int terminals_from = -1;
  // A turn limit between consecutive moves (waits between them do not count), with the vertices'
  // positions and the direction it arrives at `start` with (zero: any). A state keeps the
  // direction of the first path that reached it: every path found keeps the limit, but a path
  // that needs another direction into a state already reached may be missed.
  const std::vector<Vec3>* position = nullptr;
  double max_turn_rad = kPi;
  Vec3 heading = Vec3::Zero();
};

struct SpaceTimeAnswer {
  bool found = false;
  SpaceTimePath path;   // from start_t, ends where the agent reaches its goal (to stay)
  int cost = 0;         // path.size() - 1
  int lower_bound = 0;  // no path that keeps off `forbidden` is shorter
  int meetings = 0;     // entries of `avoided` met
  std::uint64_t expanded = 0;
};

class SpaceTimeSearch {
 public:
  // The path from query.start to query.goal; not found when the forbidden entries wall it in
  // or when `stop` holds.
  SpaceTimeAnswer find(const SpaceTimeGraph& g, const SpaceTimeQuery& q, const StopCondition& stop);

 private:
  struct Node {
    int v, t, parent, meetings, f;
    int came_from;  // the vertex its last move left (-1: none yet)
  };
  void push(const Node& n);
  bool first_visit(int v, int t, int still);
  int pop_focal();
  void raise_bound(int bound);
  bool worse(int a, int b) const;
  SpaceTimePath path_to(int node) const;

  std::vector<Node> nodes_;
  FlatCounts generated_;
  std::vector<int> live_;                // open nodes per f
  std::vector<std::vector<int>> later_;  // open nodes per f above the focal bound
  std::vector<int> focal_;               // heap of node indices
  int bound_ = 0;
};

}  // namespace uavplan
