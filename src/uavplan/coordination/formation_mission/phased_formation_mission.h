// Mission `formation_mission` (P5 sec. 1.2, fig. 1): a formation's whole flight in five phases.
// 1. Form-up: the UAVs taxi to the threshold and take off in turn, climb to altitude layers
//    100 m apart, gather under the consensus laws into the shape enlarged x3, converge to the
//    shape's heights, and shrink to it (each step ends when the shape error is under 5 m).
// 2. Mission: pso_mpc's waypoints (P5's coarse planning) from the departure point through the task
//    points with their entry headings, flown by the formation under consensus control (fine
//    planning: formation_group.h).
// 3. Return in formation towards the landing cylinder, until within 30 km of the airfield.
// 4. Dismiss, the reverse of form-up: enlarge x3, then altitude layers.
// 5. Landing, each UAV in turn (landing.h, eq. 2).
// Quantities P5 leaves out are papers.md P5's defaults (FormationMissionOptions).
#pragma once

#include "uavplan/coordination/formation_mission/landing.h"
#include "uavplan/coordination/formation_mission/task_points.h"
#include "uavplan/coordination/mission.h"

namespace uavplan {

// Mission parameters (planner.params / --set): layer_spacing_m, enlargement, shape_tolerance_m,
// form_up_height_m, takeoff_interval_s, dismiss_within_m; the rest are fixed here.
// The lengths below are P5's (its 150 m/s aircraft); plan() scales them to the formation's
// (scale_to_formation) unless planner.params names them.
struct FormationMissionOptions {
  double layer_spacing_m = 100.0;
  double enlargement = 3.0;
  double shape_tolerance_m = 5.0;
  double scale_rate_per_s = 1.0 / 30.0;  // the shape shrinks / grows by its size in 30 s
  double form_up_height_m = 1000.0;      // above the airfield (the lowest layer's reference)
  double departure_after_runway_m = 15000.0;
  double dismiss_within_m = 30000.0;  // of the airfield (papers.md P5: 20 km; ours leaves room to dismiss)
  double taxi_mps = 10.0;
  double takeoff_interval_s = 20.0;  // least time between two lift-offs
  double join_above_m = 50.0;        // above the airfield a UAV off the runway joins the consensus
  double step_timeout_s = 1800.0;    // a form-up or dismiss step that takes longer fails
  // The take-off roll: lift-off within this fraction of the runway, accelerating at least so.
  double lift_off_within_runway = 0.4;
  double min_roll_accel_mps2 = 3.0;
  // A UAV without its own turn-rate limit turns at the rate of this bank at cruise; one without
  // its own climb-rate limit climbs at most this fast (papers.md P5).
  double bank_deg = 30.0;
  double max_climb_rate_mps = 20.0;
  double max_vertical_accel_mps2 = 7.0;  // PX4's TECS default FW_T_VERT_ACC
  // The formation turns at this fraction of its slowest UAV's turn rate (margin for the shape
  // turning as a body); its route is planned for a body widened by the overshoot of a turn of
  // overshoot_turn_deg.
  double turn_margin = 0.8;
  double overshoot_turn_deg = 30.0;
  double steering_switch_m = 300.0;  // RouteSteering: a waypoint is passed within this distance
  LandingOptions landing;            // phase 5 (landing.h)

  static FormationMissionOptions from_params(const Params& params);

  // The declaration of its parameters: reads them from r (params.h).

  static FormationMissionOptions read(ParamReader& r);
};

class PhasedFormationMission final : public Mission {
 public:
  const MissionDeclaration& declaration() const override;
  // `shape`, `airfield`, `task_points`, `topology`; no goals: the UAVs land on the runway
  // (formation_mission_rules.cpp).
  void read_section(const Section& mission, const Section& uavs, Scenario& scenario) const override;
  std::string describe(const Scenario& scenario) const override;
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
  // The airfield's rule (contract/separation.h): separation in the air, bodies on the ground.
  void check_pair(const Scenario& scenario, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                  const Trajectory& tb, double need_m, Violations& out) const override;
  // The task points reached by the formation's reference in order at their entry headings,
  // every UAV ending stopped on the runway.
  void check_plan(const Scenario& scenario, const FlownUavs& flown, Violations& out) const override;
  // In the air only (on the ground bodies count, and a landed UAV is gone).
  std::optional<double> pair_distance_m(const Scenario& scenario, const UavSpec& a, const Trajectory& ta,
                                        const UavSpec& b, const Trajectory& tb) const override;
};

}  // namespace uavplan
