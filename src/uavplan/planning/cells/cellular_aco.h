// P2's cellular ant colony (Li et al. 2017) on the cell graph (cell_graph.h): ants walk from
// cell to cell choosing P ~ tau^alpha eta^beta (eq. 3), pheromone evaporates with a rate that
// grows x1.05 per iteration up to rho_max (eq. 4-5), ants deposit Q / J_k on the cells they
// used (eq. 6), tau is clamped to [tau_min, tau_max] (eq. 7), and after every iteration the
// best route goes through the cellular-automaton update: its cells die where the neighbours
// join directly at lower cost, or move to a neighbour cell that lowers the cost, until none does.
// Ants run in parallel, each with its own random stream (seed, leg, iteration, ant), so the
// result does not depend on the thread count.
#pragma once

#include "uavplan/planning/cells/cell_route.h"

namespace uavplan {

struct CellularAcoOptions {
  CellPlanOptions cells;
  int ants = 100;
  int iterations = 25;
  double alpha = 3.0;        // pheromone weight (P2)
  double beta = 2.0;         // heuristic weight (P2)
  double q = 100.0;          // deposit constant (P2)
  double rho0 = 0.1;         // initial evaporation
  double rho_max = 0.5;      // evaporation cap
  double tau_max = 1.0;      // pheromone bounds, relative: deposits are scaled by J_best / Q so that
  double tau_min = 0.01;     //   the best ant deposits 1 whatever the cost's units
  int max_steps_factor = 8;  // an ant dies after this many times the straight-line cell count
  int threads = 0;           // 0 = the run's (--threads, else every core)
  bool local_update = true;  // the cellular-automaton update of the best route
  static CellularAcoOptions from_params(const Params& params);
  // The declaration of its parameters: reads them from r (params.h).
  static CellularAcoOptions read(ParamReader& r);
};

struct AcoLegReport {
  int iterations = 0;
  int ants_arrived = 0;
  double best_cost = 0.0;
};

// The colony's best node path on the graph for one leg.
std::optional<std::vector<std::int64_t>> cellular_aco_search(const CellGraph& g, std::int64_t from, std::int64_t to,
                                                             const CellularAcoOptions& options, std::uint64_t seed,
                                                             int leg, const StopCondition& stop, PlanStats& stats,
                                                             AcoLegReport* report = nullptr);

class CellularAcoPlanner final : public Planner {
 public:
  explicit CellularAcoPlanner(CellularAcoOptions options = {}) : options_(options) {}
  std::string_view name() const override { return "cellular_aco"; }
  const CellularAcoOptions& options() const { return options_; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  CellularAcoOptions options_;
};

}  // namespace uavplan
