// The legs of a trajectory that take off from and land on the ground: at the start, from a row
// on the ground up to the first row off it and on along the vertical column above the start;
// at the end, the same backwards. On them a UAV is exempt from the climb and turn limits and
// min_agl, and from the ground it stands on within its radius and clearance (verifier.h).
#pragma once

#include <cstddef>

#include "uavplan/simulation/trajectory.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct GroundLegs {
  bool takeoff = false, landing = false;
  std::size_t takeoff_end = 0, landing_begin = 0;  // rows
  // Whether the segment from row segment_end - 1 to row segment_end is on a ground leg.
  bool covers(std::size_t segment_end) const {
    return (takeoff && segment_end <= takeoff_end) || (landing && segment_end - 1 >= landing_begin);
  }
  std::size_t airborne_begin() const { return takeoff ? takeoff_end : 0; }
  std::size_t airborne_end(std::size_t rows) const { return landing ? landing_begin : rows - 1; }
};

GroundLegs ground_legs(const World& world, const Trajectory& trajectory);

}  // namespace uavplan
