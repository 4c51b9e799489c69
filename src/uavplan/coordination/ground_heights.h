// How high above the ground the planners keep the UAVs of a scenario, and where a UAV can stand
// on it: the scenario's min_agl and max_agl for all its UAVs, the default height a take-off ends
// at, and each vertical take-off or landing column. Used by the planning view (planning_view.h)
// and the arrival points (contract/arrival_points.h) alike.
#pragma once

#include <optional>
#include <string>

#include "uavplan/coordination/contract/scenario.h"

namespace uavplan {

// The largest min_agl of the scenario's UAVs, or its default_min_agl_m where larger: the ground
// the planners keep clear for all of them.
double planning_min_agl_m(const Scenario& scenario);

// What a UAV that takes off or lands flies above the ground when its scenario sets no min_agl:
// PX4's default take-off height (MIS_TAKEOFF_ALT, 2.5 m), so that a flight from the ground does
// not cruise a hand's breadth above it. Less where the scenario has less room: every start, goal
// and via point in the air stays above it (with its body), every lift-off fits under the top of
// the world and the UAV's ceiling with its column clear; 0 in a flat world, for a
// formation_mission (its UAVs fly from a runway by P5's phases) and where no UAV without
// min_agl touches the ground.
inline constexpr double kDefaultMinAgl_m = 2.5;
// The smallest max_agl of the scenario's UAVs (none: no UAV sets one): the band's top the
// planners keep for all of them. Without terrain it is a ceiling over the floor; over terrain a
// box above each cell, which planners keep their bodies below.
std::optional<double> planning_max_agl_m(const Scenario& scenario);
double default_min_agl_m(const Scenario& scenario);
// How high above the ground a UAV standing on it lifts off vertically before it is planned: its
// body, its clearance and the planning min_agl clear of the ground, with a 5 cm margin.
double lift_height_m(const Scenario& scenario, const UavSpec& uav);
// Why a UAV cannot stand on the ground at p (its vertical take-off or landing column up to the
// lift height is not clear of obstacles and of terrain beside it), or empty.
std::string ground_column_problem(const Scenario& scenario, const UavSpec& uav, const Vec3& p);
// The same for a column `lift_m` high above the ground at p.
std::string vertical_column_problem(const Scenario& scenario, const UavSpec& uav, const Vec3& p, double lift_m);

}  // namespace uavplan
