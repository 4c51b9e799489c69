// Moving obstacles with a known constant velocity.
#pragma once

#include <string>

#include "uavplan/core/vec.h"

namespace uavplan {

struct MovingObstacle {
  std::string id;
  double radius_m = 0.0;
  Vec3 position;            // at t = 0
  Vec3 velocity_mps = Vec3::Zero();

  Vec3 position_at(double t_s) const { return position + t_s * velocity_mps; }
};

}  // namespace uavplan
