// P2's baseline, done right: A* on the same cell graph with the same cost (cell_graph.h) and an
// admissible heuristic (the straight line's range term), so its route is optimal for that cost.
#pragma once

#include "uavplan/planning/cells/cell_route.h"

namespace uavplan {

struct CellAStarOptions {
  CellPlanOptions cells;
  static CellAStarOptions from_params(const Params& params);
  // The declaration of its parameters: reads them from r (params.h).
  static CellAStarOptions read(ParamReader& r);
};

// Optimal node path on the graph (A*); nothing when the goal is unreachable or the stop came
// first (the caller tells the two apart by asking the stop).
std::optional<std::vector<std::int64_t>> cell_astar_search(const CellGraph& g, std::int64_t from, std::int64_t to,
                                                           PlanStats& stats, const StopCondition& stop = {});

class CellAStarPlanner final : public Planner {
 public:
  explicit CellAStarPlanner(CellAStarOptions options = {}) : options_(options) {}
  std::string_view name() const override { return "cell_astar"; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  CellAStarOptions options_;
};

}  // namespace uavplan
