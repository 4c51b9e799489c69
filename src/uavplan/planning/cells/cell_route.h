// What P2's cell planners share: the cell map and graph for a problem, the attachment of the
// start, via points and goal to nodes, and the assembly of per-leg node paths into a checked
// route (Start -> task 1 -> task 2 -> ... -> Finish).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/planning/cells/cell_graph.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"

namespace uavplan {

struct CellPlanOptions {
  double cell_m = 0.0;   // 0 = the terrain's cell, else the bounds / 64
  double level_m = 0.0;  // 0 = cell_m / 2
  CellCostWeights weights;

  // Reads cell_m, level_m, w1, w2, w3.
  void read(ParamReader& r);
};

// A node path from `from` to `to` (both included), or nothing; `stop` is the leg's own (an
// anytime search returns its best path when it holds).
using CellLegSearch = std::function<std::optional<std::vector<std::int64_t>>(
    const CellGraph& g, std::int64_t from, std::int64_t to, int leg, PlanStats& stats, const StopCondition& stop)>;

PlanResult plan_on_cells(const Problem& problem, const World& world, const CellPlanOptions& options,
                         const StopCondition& stop, const CellLegSearch& search);

// P2's penalty J of a route under the graph's cost (sum over its segments).
double cell_route_cost(const CellGraph& g, const std::vector<Vec3>& waypoints);

// The map and graph plan_on_cells builds for this problem (for benchmarks and tests). The graph
// points into the map, so a CellWorld stays where it was built.
struct CellWorld {
  CellWorld(const Problem& problem, const World& world, const CellPlanOptions& options, const StopCondition& stop = {});
  CellWorld(const CellWorld&) = delete;
  CellWorld& operator=(const CellWorld&) = delete;
  CellMap map;
  CellGraph graph;
};

}  // namespace uavplan
