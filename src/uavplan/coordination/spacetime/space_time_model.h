// What the high levels (prioritised planning, CBS and ECBS) ask of a multi-agent problem in space
// and time: each agent's own search under a table of constraints, the entries an agent's path
// puts in another's table, and the conflicts among paths. Grid MAPF (a vertex at one time, a
// swap in one step) is one model (mapf.h); UAVs on a lattice, their conflicts found exactly on
// their trajectories, another (uav_lattice.h).
#pragma once

#include <optional>
#include <vector>

#include "uavplan/coordination/spacetime/safe_interval_astar.h"
#include "uavplan/coordination/spacetime/space_time_astar.h"
#include "uavplan/coordination/spacetime/space_time_table.h"
#include "uavplan/core/stop.h"

namespace uavplan {

// One agent's part of a conflict, as the constraint that forbids it: not at v at time t (u < 0),
// or not moving v -> u in step t (u == v: not waiting at v in step t).
struct AgentStep {
  int agent = 0;
  int v = 0, u = -1, t = 0;
};

// Two agents' parts that cannot both happen; every solution lacks one of them.
struct PathConflict {
  AgentStep a, b;
};

// The searches' buffers, kept between queries by the high level that owns them: the
// time-expanded focal search, and the safe-interval search for hard constraints alone.
struct SpaceTimeSearches {
  SpaceTimeSearch expanded;
  SafeIntervalSearch intervals;
};

class SpaceTimeModel {
 public:
  virtual ~SpaceTimeModel() = default;
  virtual int agent_count() const = 0;
  virtual int vertex_count() const = 0;
  // Agent i's path, or none, keeping off `forbidden` and meeting `avoided` (may be null) as
  // seldom as a path within w of the shortest can.
  virtual SpaceTimeAnswer plan(int agent, const SpaceTimeTable& forbidden, const SpaceTimeTable* avoided, double w,
                               SpaceTimeSearches& search, const StopCondition& stop) const = 0;
  // Steps of agent i's path alone (prioritised planning takes the longest first).
  virtual int lone_cost(int agent) const = 0;
  // What agent i's path forbids the others, into `table`.
  virtual void add_path(int agent, const SpaceTimePath& path, SpaceTimeTable& table) const = 0;
  // The earliest conflict among the paths, if any.
  virtual std::optional<PathConflict> first_conflict(const std::vector<SpaceTimePath>& paths) const = 0;
  // How many conflicts the paths have (ECBS's focal order).
  virtual int count_conflicts(const std::vector<SpaceTimePath>& paths) const = 0;
};

}  // namespace uavplan
