// Moving obstacles: a constant velocity from a position at t = 0, or a piecewise-linear path
// of time-stamped points (before its first row at its first point, after its last row at its
// last point).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

struct TimedPoint {
  double t_s = 0.0;
  Vec3 p = Vec3::Zero();
};

struct MovingObstacle {
  std::string id;
  double radius_m = 0.0;
  Vec3 position = Vec3::Zero();  // at t = 0 (constant velocity)
  Vec3 velocity_mps = Vec3::Zero();
  std::vector<TimedPoint> path = {};  // when not empty, the motion (position and velocity unused)

  Vec3 position_at(double t_s) const;
  // The velocity at t (the later piece's at a row; zero before and after the path).
  Vec3 velocity_at(double t_s) const;
  // The times at which the velocity may change: the path's rows (none for a constant velocity).
  std::span<const TimedPoint> rows() const { return path; }
};

}  // namespace uavplan
