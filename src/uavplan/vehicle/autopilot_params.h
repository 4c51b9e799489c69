// The time constants of P5's autopilot model (autopilot.h), a UAV's `model` in a scenario.
#pragma once

namespace uavplan {

// Time constants (s). Defaults: papers.md P5 (the classic close-formation autopilot values;
// P5 gives none).
struct AutopilotParams {
  double tau_v_s = 5.0;
  double tau_heading_s = 0.75;
  double tau_zdot_s = 0.3075;
  double tau_z_s = 3.85;
};

}  // namespace uavplan
