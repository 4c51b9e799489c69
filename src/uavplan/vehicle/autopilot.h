// P5 eq. 1 as cleaned in papers.md P5: a 3-DOF kinematic model with speed, altitude and
// heading holds (lateral and longitudinal decoupled),
//   x' = v cos phi,  y' = v sin phi,
//   z'' = -z'/tau_zdot + (z_c - z)/tau_z,
//   v'  = (v_c - v)/tau_v,
//   phi' = (phi_c - phi)/tau_heading   (the difference wrapped to (-pi, pi]),
// integrated with Boost.Odeint (fixed-step RK4), with the vehicle's limits as saturations: the
// commanded speed within [min, max], the turn rate within max_turn_rate, the climb rate within
// max_climb_rate, the vertical acceleration within max_vertical_accel. And a waypoint follower that flies a route through it.
#pragma once

#include <limits>
#include <vector>

#include "uavplan/core/vec.h"
#include "uavplan/vehicle/autopilot_params.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {

struct AutopilotLimits {
  SpeedLimits speed;
  double max_turn_rate_rad_s = std::numeric_limits<double>::infinity();
  double max_climb_rate_mps = std::numeric_limits<double>::infinity();
  // |z''|: an autopilot's vertical acceleration limit (PX4's TECS: FW_T_VERT_ACC).
  double max_vertical_accel_mps2 = std::numeric_limits<double>::infinity();
};

struct AutopilotState {
  Vec3 position = Vec3::Zero();
  double climb_rate_mps = 0.0;  // z'
  double speed_mps = 0.0;       // horizontal speed v_xy
  double heading_rad = 0.0;     // 0 = east, pi/2 = north
};

struct AutopilotCommand {
  double speed_mps = 0.0;
  double altitude_m = 0.0;
  double heading_rad = 0.0;
};

class AutopilotModel {
 public:
  // Throws std::invalid_argument on a time constant or integration step <= 0.
  AutopilotModel(AutopilotParams params, AutopilotLimits limits, double step_s = 0.05);
  // The state dt_s later under a command held constant.
  void advance(AutopilotState& state, const AutopilotCommand& command, double dt_s) const;
  const AutopilotParams& params() const { return p_; }
  const AutopilotLimits& limits() const { return lim_; }
  double step_s() const { return step_s_; }

 private:
  AutopilotParams p_;
  AutopilotLimits lim_;
  double step_s_;
};

struct FollowOptions {
  double sample_s = 1.0;  // one row of the flown path per this much time (and at the end)
  double max_time_s = 1e6;
  // A waypoint is passed when within this distance, or when the UAV is past it along the leg
  // into it; 0: where an arc of the turn radius R at cruise through the corner begins,
  // R tan(turn / 2) before it (turns above 90 deg as 90), at least 2 v tau_heading.
  double switch_radius_m = 0.0;
  // Waypoints (by index) to fly over, not turn short of: passed at the closest approach once within
  // two integration steps' flight, with a row there (via points a plan must visit).
  std::vector<char> fly_over;
};

struct FollowSample {
  double t_s = 0.0;
  AutopilotState state;
};

struct FollowResult {
  std::vector<FollowSample> samples;  // from t = 0, every sample_s, and the last state
  bool reached = false;               // the last waypoint passed within max_time_s
  double closest_to_goal_m = std::numeric_limits<double>::infinity();
};

// Flies the waypoints in turn at cruise speed: heading command the bearing to the current
// waypoint, altitude command its altitude. The last waypoint counts as reached when the UAV
// comes within max(2 v h, v tau_heading) of it (h the integration step).
FollowResult follow_waypoints(const AutopilotModel& model, AutopilotState start, const std::vector<Vec3>& waypoints,
                              double cruise_mps, const FollowOptions& options = {});

// The switch radius that `options` gives for `model` at cruise speed before a turn of turn_rad.
double switch_radius_m(const AutopilotModel& model, double cruise_mps, double turn_rad, const FollowOptions& options);

}  // namespace uavplan
