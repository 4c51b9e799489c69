// Where each UAV ends. Aircraft cannot share a point: UAVs whose goals lie closer than
// max(mission.goal_spacing, their separation) share a goal, and end at distinct points of a
// horizontal ring around their goals' centroid (radius max(chord, chord / (2 sin(pi / k))) for k
// UAVs, chord = max(goal_spacing, separation)): each at the bearing of its start, neighbours
// pushed apart until they are a chord apart, so that UAVs coming from one side arrive side by
// side. The ring turns in 15-degree steps until every point is free (in the bounds, body and
// clearance clear of obstacles and terrain, min_agl above the ground, or on the ground when the
// goals are).
// The verifier accepts a UAV's end anywhere within tolerance_m of its goal (its ring point's
// distance from the goal) and checks the separation at the goals like anywhere else.
#pragma once

#include <string>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

struct Arrival {
  Vec3 point;                // where the UAV ends (its goal when it shares it with nobody)
  double tolerance_m = 0.0;  // how far from its goal it may end
  std::string problem;       // non-empty: a shared goal without free ring points
};

// Per UAV in scenario order; a UAV without a goal gets its start and tolerance 0.
std::vector<Arrival> arrival_points(const Scenario& scenario);

// Arrival (contract): the time a UAV reaches its goal, within its radius (0.5 m at least) plus
// the goal's tolerance, and stays there to the end of its trajectory; +inf when its trajectory
// does not end there. Hovering at the goal while others come is arriving early.
inline constexpr double kMinArrivalRadius_m = 0.5;
double arrival_radius_m(const UavSpec& uav, const Arrival& arrival);
double arrival_time_s(const Trajectory& trajectory, const Vec3& goal, double within_m);
// The first time a row comes within the radius (a UAV with a home leaves its goal again).
double first_arrival_s(const Trajectory& trajectory, const Vec3& goal, double within_m);
// A UAV's arrival by the contract (+inf: it has no goal or never stays at it).
double arrival_s(const UavSpec& uav, const Arrival& arrival, const Trajectory& trajectory);

// The spacing of UAVs at a shared goal: mission.goal_spacing, else the separation; never below
// the separation of the pair or their radii plus clearances (a smaller value has no effect).
double goal_spacing_m(const Scenario& scenario, const UavSpec& a, const UavSpec& b);

}  // namespace uavplan
