// Multi-agent path finding on a space-time graph (unit moves and waits; no two agents at one
// vertex at one time, none swapping in one step; an agent stays at its goal once there): the
// problem, the methods, and the one entry point that picks among them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "uavplan/coordination/spacetime/space_time_graph.h"
#include "uavplan/coordination/spacetime/space_time_table.h"
#include "uavplan/core/status.h"
#include "uavplan/core/stop.h"

namespace uavplan {

struct MapfProblem {
  SpaceTimeGraph graph;
  std::vector<int> starts, goals;  // one each per agent; starts distinct, goals distinct
};

enum class MapfMethod {
  automatic,    // ECBS with 3/4 of the time limit, then prioritised planning with the rest
  prioritized,  // one agent after another around the paths before (Silver 2005), reordered on failure
  ecbs,         // bounded-suboptimal conflict-based search (Barer et al. 2014), cost <= w * optimal
  cbs,          // conflict-based search (Sharon et al. 2015): the least sum of costs
};

struct MapfOptions {
  MapfMethod method = MapfMethod::automatic;
  double w = 1.3;  // ECBS's suboptimality bound (libMultiRobotPlanning's benchmark value)
  int orders = 8;  // prioritised planning: agent orders tried (each puts the last one that failed first)
  StopCondition stop;
};

// solved, or failed for stopped, no_route (an agent cannot reach its goal), budget (the
// high-level nodes) or conflict (no conflict-free solution found).
struct MapfResult : Outcome {
  std::vector<SpaceTimePath> paths;  // one per agent when solved
  int sum_of_costs = 0, makespan = 0;
  // No solution's sum of costs is lower: the lone shortest paths' sum, or a conflict-based
  // search's bound where it ran.
  int lower_bound = 0;
  std::string method;  // what found it ("prioritized (order 2)", "ecbs w=1.3", "cbs")
  std::uint64_t high_level_nodes = 0, low_level_expansions = 0;
};

// Every agent's distances to its goal are kept (the searches' heuristic): at most this much.
inline constexpr std::uint64_t kMostDistanceTableBytes = std::uint64_t{1} << 30;

// The problem's mistakes (a start or goal off the graph, two agents sharing one, distance tables
// beyond kMostDistanceTableBytes); empty when it can be searched.
std::string mapf_problem_mistake(const MapfProblem& problem);

// Solves `problem`; std::invalid_argument for a mistaken problem or option.
MapfResult solve_mapf(const MapfProblem& problem, const MapfOptions& options);

class SpaceTimeModel;
// Solves a problem given as a space-time model (space_time_model.h) by options.method.
MapfResult solve_space_time(const SpaceTimeModel& model, const MapfOptions& options);

const char* to_string(MapfMethod m);
// "auto", "prioritized", "ecbs", "cbs"; false for another word.
bool parse_mapf_method(const std::string& word, MapfMethod& out);

}  // namespace uavplan
