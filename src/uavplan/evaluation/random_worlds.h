// Random worlds for property tests and soaks: a box of mixed obstacles (spheres, cylinders,
// boxes, prisms, sometimes terrain), flat or 3-D, and UAVs with starts and goals in free space
// and random limits. Seeded: the same seed gives the same scenario.
#pragma once

#include <cstdint>

#include "uavplan/coordination/contract/scenario.h"

namespace uavplan {

struct RandomWorldOptions {
  int max_uavs = 3;
  bool limits = true;  // random turn and climb limits on some UAVs
  std::string mission = "independent";
  // 3-D worlds: about half the starts and goals on the ground, and random clearance and min_agl.
  bool ground_and_margins = false;
};

Scenario random_world(std::uint64_t seed, const RandomWorldOptions& options = {});

// P1's formation mission on a random flat field (the kind of world issue targets name): 400-1000 m,
// 5-30 radars, 0-4 no-fly cylinders, 3-7 UAVs in a wedge, line abreast or column from one
// take-off place to one landing place, sensors of 20-100 m, and 1-4 moving obstacles crossing,
// meeting head-on or turning across the straight line between the two places.
Scenario random_formation_world(std::uint64_t seed);

// P1's local layer on a route: a flat field of 200-600 m with 0-6 cylinders, a `route` mission
// of 1-3 via points, 1-3 UAVs with 20-60 m sensors, and a moving obstacle before most via points
// (parked, crossing or head-on), meeting the first UAV 2-10 m short of the via point (a parked
// one leaves room to pass the via point beside it): a detour around it that rejoined one step
// past the obstacle would skip the via point.
Scenario random_via_world(std::uint64_t seed);

// P5's coarse planning at scale (issue targets): 100-1000 km square, 10 km high, 5-20 no-fly
// cylinders of 10-60 km, one fixed-wing UAV (70/150/200 m/s, 30 deg turns, P5's autopilot model)
// from near one corner, 1-3 via points with random entry headings (multiples of 45 deg), a goal.
Scenario random_p5_world(std::uint64_t seed);

// P5's whole formation mission (issue targets): 300-1000 km square, 10 km high, an airfield
// anywhere at least 60 km from the edges with a random runway heading and a 2-4 km runway, 3-6
// UAVs parked beside the runway or behind its threshold, a wedge, line abreast, column or diamond
// (sometimes stepped in height) 60-150 m apart, separation 50 m, the complete or a ring topology,
// 2-5 task points at 3-7 km with random entry headings, 5-15 no-fly cylinders of 10-60 km kept
// clear of the task points and the airfield's approach and departure, P5's vehicle or one near it.
Scenario random_formation_mission(std::uint64_t seed);

// A world whose first UAV's goal sits in a closed hollow box: no route can reach it.
Scenario enclosed_goal_world(std::uint64_t seed);

}  // namespace uavplan
