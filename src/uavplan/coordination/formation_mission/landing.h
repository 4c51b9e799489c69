// P5 phase 5: the UAVs land one after another (P5 eq. 2). Each, in turn, flies through its
// autopilot model to the landing cylinder, spirals down inside it, lines up with the runway and
// touches down; its speed is the fastest in [v_min, v_max] whose flight conflicts with none of
// those planned before it (the earliest landing, eq. 2 with mu = 1), else it first holds one more
// circle and tries again. Geometry (P5 gives none; papers.md P5): the cylinder of radius
// 3 km centred 10 km before the threshold on the extended centreline, descent at most 10 m/s,
// the gate 300 m above the runway 6 km out, a straight glide onto the runway, the roll-out
// ending within the runway's first half.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/status.h"
#include "uavplan/simulation/trajectory.h"
#include "uavplan/vehicle/autopilot.h"

namespace uavplan {

struct LandingOptions {
  double cylinder_radius_m = 3000.0;
  double cylinder_before_threshold_m = 10000.0;
  double max_descent_mps = 10.0;
  double gate_height_m = 300.0;
  double gate_before_threshold_m = 6000.0;
  double speed_step_mps = 5.0;  // the speeds tried, from the fastest down
  int max_holds = 12;
  double sample_s = 1.0;
};

// solved, or failed for conflict (no landing at any speed within the holds keeps clear).
struct LandingResult : Outcome {
  Trajectory flight;       // from the state it starts in until it stops on the runway
  double speed_mps = 0.0;  // the speed eq. 2 chose
  int holds = 0;
};

// The landing of one UAV from `state` at t0_s, conflict-free with `conflicts(flight)` false.
LandingResult plan_landing(const Airfield& airfield, const AutopilotModel& model, const AutopilotState& state,
                           double t0_s, const LandingOptions& options,
                           const std::function<bool(const Trajectory&)>& conflicts);

}  // namespace uavplan
