// Group planning with the potential field (P3 sec. 2): UAVs numbered 1..N plan in turn, one
// time frame at a time; after UAV i plans frame T its position becomes an obstacle that exists
// only at frame T for the UAVs planning after it (they keep the separation from its motion over
// the frame). Our addition: UAVs not yet moved in frame T are obstacles at their frame T-1
// positions, so the earlier ones cannot step onto them. A UAV at its goal is skipped and stays
// there as an obstacle. Afterwards every path gets P3's triple smoothing; a smoothed point that
// would touch an obstacle, come closer to another UAV than the separation at equal times, or
// drift more than kDrift_steps steps from its raw place keeps its original place (the drift
// bound lets the conflict check skip UAVs that are never near).
#pragma once

#include <string>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/stop.h"
#include "uavplan/planning/field/apf.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

struct GroupUav {
  std::string id;
  bool reached = false;
  std::string message;
  std::vector<Vec3> raw;       // position at every frame until arrival
  std::vector<Vec3> smoothed;  // the same frames after smoothing (== raw without smoothing)
  int smoothed_points = 0;
  int kept_points = 0;  // smoothing moves refused for a conflict
};

struct GroupResult {
  double frame_s = 0.0;  // time between frames
  double step_m = 0.0;
  int frames = 0;
  std::vector<GroupUav> uavs;
};

inline constexpr double kDrift_steps = 1.0;

// options.separation_m is taken from the scenario's mission.
GroupResult plan_group(const Scenario& scenario, const ApfOptions& options, const StopCondition& stop);

// Frame positions as a trajectory (frame k at k * frame_s).
Trajectory frames_to_trajectory(const std::vector<Vec3>& frames, double frame_s);

}  // namespace uavplan
