// Conflicts between agents' space-time paths (unit steps): two agents at one vertex at one time,
// or two swapping vertices in one step. The one scan serves the conflict-based search (its first
// conflict, its count of conflicts) and the check of a finished solution.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "uavplan/coordination/spacetime/space_time_graph.h"
#include "uavplan/coordination/spacetime/space_time_table.h"

namespace uavplan {

struct MapfConflict {
  int a = 0, b = 0;  // agents, a < b
  int t = 0;         // a vertex conflict's time; a swap's step is t -> t + 1
  int v = 0;         // the vertex; a swap: a moves v -> u, b moves u -> v
  int u = -1;        // -1: a vertex conflict
  bool swap() const { return u >= 0; }
};

// The earliest conflict (by time; at one time vertex conflicts before swaps, then by agents).
std::optional<MapfConflict> first_conflict(const std::vector<SpaceTimePath>& paths, int vertex_count);
// How many conflicts: per time, each agent that joins a vertex already taken, and each swap.
int count_conflicts(const std::vector<SpaceTimePath>& paths, int vertex_count);

// Why `paths` are not a solution of the problem (a path that does not start at its start or end
// at its goal, a step that is no edge of the graph, a conflict); nothing when they are.
std::optional<std::string> mapf_solution_problem(const SpaceTimeGraph& g, const std::vector<int>& starts,
                                                 const std::vector<int>& goals,
                                                 const std::vector<SpaceTimePath>& paths);

int sum_of_costs(const std::vector<SpaceTimePath>& paths);
int makespan(const std::vector<SpaceTimePath>& paths);

}  // namespace uavplan
