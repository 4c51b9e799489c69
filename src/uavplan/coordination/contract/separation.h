// Separation between UAVs: how far apart two UAVs must stay (at their goals too: UAVs sharing a
// goal end at distinct points, arrival_points.h).
#pragma once

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

// The distance UAVs a and b must keep: the mission's separation, and never less than the sum
// of their radii.
double required_separation_m(const Scenario& scenario, const UavSpec& a, const UavSpec& b);

// formation_mission (contract): the separation holds whenever either UAV of a pair is more than
// kAirborneAbove_m above the airfield; below, on the ground, their bodies never touch. A UAV is
// parked at its first row before it and gone after its last (taxied off). Between the merged
// rows both move linearly, so each piece's closest distance is exact; a piece with either UAV
// high at either end needs the separation.
inline constexpr double kAirborneAbove_m = 10.0;
struct AirfieldEncounter {
  bool conflict = false;
  double t_s = 0.0, distance_m = 0.0, need_m = 0.0;
  Vec3 where = Vec3::Zero();            // a's position then
  double airborne_min_m = World::kInf;  // their smallest distance while either is in the air
};
AirfieldEncounter airfield_encounter(const Scenario& scenario, const UavSpec& ua, const Trajectory& a,
                                     const UavSpec& ub, const Trajectory& b, double from_s = -1e300);

}  // namespace uavplan
