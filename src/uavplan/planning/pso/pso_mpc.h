// P5 secs. 2.1-2.2: multi-step PSO waypoints with model-predictive look-ahead. One waypoint per
// step: U = (dphi, dh) puts the next waypoint Q at horizontal distance l from the current one P,
// at heading psi + dphi and height h + dh (eq. 3); the PSO minimises
//   J_sp = |SP - T| + alpha |h_SP - h_T|            (eq. 5, SP = P + (1 + prediction) (Q - P))
// with both P->Q and its extension Q->SP clear of the no-fly zones (death penalty), and near the
// target (papers.md P5): for d_t < d <= d_tar the final-turn term beta |dphi_tar| (deg) is
// added (eq. 7), for d <= d_t it is taken at Q without prediction (eq. 8); for 2 l <= d < 3 l the
// last turn and climb are hard (eq. 6); below 2 l the target is the last waypoint. With an entry
// heading phi_r at a via point, the target is T_tar = T_task - l (cos phi_r, sin phi_r, 0), the
// term gamma |dphi_task| (eqs. 10-12), and the fixed segment T_tar -> T_task closes the leg.
#pragma once

#include "uavplan/core/pso.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"

namespace uavplan {

struct PsoMpcOptions {
  // l (m). 0: P5's 5000 m for worlds of 200 km and more, else 1/40 of the world's larger
  // horizontal side; never less than the chord a turn-rate-limited UAV needs to turn dphi_max
  // (2 R sin(dphi_max / 2), R = cruise / turn rate).
  double step_m = 0.0;
  double max_turn_deg = 30.0;  // dphi_max (P5 Table 1); never more than the UAV's turn limit
  // dh_max (m). 0: l tan(climb), the climb the UAV's limit, else P5's atan(300 / 5000).
  double max_dh_m = 0.0;
  double alpha = 10.0;  // P5 Table 1
  // Per degree, as multiples of l: P5's beta = 800 and gamma = 5000 at l = 5000 m.
  double beta_per_l = 0.16;
  double gamma_per_l = 1.0;
  int prediction_steps = 11;  // 0: P5's J0 (eq. 4), the look-ahead ablation
  double d_tar_l = 15.0, d_t_l = 13.0;
  // 30 particles, 100 iterations, w 0.9 -> 0.4, c1 = c2 = 2 (papers.md P5); stop after 10
  // iterations without improving by 1e-6 of the cost (about a metre in 1000 km; 20 gave routes
  // within 0.1 %), or after 20 without any feasible point (keys stall, give_up).
  PsoOptions pso{.particles = 30,
                 .iterations = 100,
                 .w_start = 0.9,
                 .w_end = 0.4,
                 .c1 = 2.0,
                 .c2 = 2.0,
                 .stall_iterations = 10,
                 .stall_tolerance = 1e-6,
                 .infeasible_iterations = 20};
  static PsoMpcOptions from_params(const Params& params);
  // The declaration of its parameters: reads them from r (params.h).
  static PsoMpcOptions read(ParamReader& r);
};

// What these options give for a UAV in a world: l, dphi_max and dh_max (the scaling above).
struct PsoSteps {
  double step_m = 0.0;
  double max_turn_rad = 0.0;
  double max_dh_m = 0.0;
};
PsoSteps pso_steps(const PsoMpcOptions& o, const UavSpec& uav, const World& world);

class PsoMpcPlanner final : public Planner {
 public:
  explicit PsoMpcPlanner(PsoMpcOptions options) : options_(options) {}
  std::string_view name() const override { return "pso_mpc"; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  PsoMpcOptions options_;
};

}  // namespace uavplan
