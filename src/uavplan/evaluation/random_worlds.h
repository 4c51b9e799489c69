// Random worlds for property tests and soaks: a box of mixed obstacles (spheres, cylinders,
// boxes, prisms, sometimes terrain), flat or 3-D, and UAVs with starts and goals in free space
// and random limits. Seeded: the same seed gives the same scenario.
#pragma once

#include <cstdint>

#include "uavplan/coordination/scenario.h"

namespace uavplan {

struct RandomWorldOptions {
  int max_uavs = 3;
  bool limits = true;          // random turn and climb limits on some UAVs
  MissionType mission = MissionType::independent;
  // 3-D worlds: about half the starts and goals on the ground, and random clearance and min_agl.
  bool ground_and_margins = false;
};

Scenario random_world(std::uint64_t seed, const RandomWorldOptions& options = {});

// A world whose first UAV's goal sits in a closed hollow box: no route can reach it.
Scenario enclosed_goal_world(std::uint64_t seed);

}  // namespace uavplan
