// P5's single-step PSO baseline (sec. 4.1): all of a leg's intermediate waypoints in one swarm.
// P5 publishes no formulation (it says the constraints were "relaxed" into the objective); ours,
// after papers.md P5: decision n waypoints (x, y, h), cost
//   sum of segment lengths + w_turn sum max(0, turn - dphi_max) [deg] + w_climb sum max(0, |dh| - dh_max)
//   + w_len sum max(0, l - segment) + w_nfz (length inside no-fly zones, sampled every l / 4),
// n = the straight line's whole steps l less one (papers.md P5: the multi-step route's count less one;
// bench p5-coarse sets that), the straight line a seed particle, the swarm 100 x 500 iterations.
// The best route is reported as found; the planner calls it solved only when it holds every limit
// and clears every obstacle (bench p5-coarse shows how often, and by how much, it does not).
#pragma once

#include "uavplan/core/pso.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"
#include "uavplan/planning/pso/pso_mpc.h"

namespace uavplan {

struct PsoSingleOptions {
  PsoMpcOptions steps;         // l, dphi_max and dh_max as pso_mpc has them
  int waypoints = 0;           // per leg; 0: floor(distance / l) - 1
  double w_turn_per_l = 1.0;   // per degree over dphi_max, as a multiple of l (P5's gamma)
  double w_climb = 10.0;       // per metre over dh_max (P5's alpha)
  double w_len = 10.0;         // per metre a segment falls short of l
  double w_nfz_per_m = 100.0;  // per metre inside a no-fly zone
  PsoOptions pso{.particles = 100,
                 .iterations = 500,
                 .w_start = 0.9,
                 .w_end = 0.4,
                 .c1 = 2.0,
                 .c2 = 2.0,
                 .stall_iterations = 50,
                 .stall_tolerance = 1e-9,
                 .infeasible_iterations = 0};
  static PsoSingleOptions from_params(const Params& params);
  // The declaration of its parameters: reads them from r (params.h).
  static PsoSingleOptions read(ParamReader& r);
};

struct SingleStepRoute {
  std::vector<Vec3> waypoints;
  double cost = 0.0;
  double worst_turn_rad = 0.0;
  std::size_t worst_turn_at = 0;  // the waypoint where it turns most
  double inside_nfz_m = 0.0;
  int evaluations = 0;
};

// The swarm's best route from the start to the goal of `problem` (via points split it into legs).
SingleStepRoute pso_single_route(const Problem& problem, const World& world, const PsoSingleOptions& options,
                                 const StopCondition& stop);

class PsoSinglePlanner final : public Planner {
 public:
  explicit PsoSinglePlanner(PsoSingleOptions options) : options_(options) {}
  std::string_view name() const override { return "pso_single"; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  PsoSingleOptions options_;
};

}  // namespace uavplan
