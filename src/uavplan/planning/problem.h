// Problem, Route and PlanResult: what a single-UAV planner takes and returns.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "uavplan/core/status.h"
#include "uavplan/core/vec.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {

struct Problem {
  UavSpec uav;  // start, start heading and limits
  Vec3 goal = Vec3::Zero();
  std::vector<Vec3> via;  // visited in order between start and goal
  // Required entry heading at each via point (0 = east, pi/2 = north), by index; shorter or
  // empty: none. Planners that do not take entry headings ignore them (registry: entry_headings).
  std::vector<std::optional<double>> via_entry_heading_rad = {};
  std::uint64_t seed = 1;  // for randomised planners: the same seed gives the same route
};

// Names for failure messages, one-based as a user counts: stop s of n (start, via point k, goal)
// and leg l of the route through n stops ("leg 2 of 3 (via point 1 to via point 2)").
std::string stop_name(std::size_t s, std::size_t stops);
std::string leg_name(std::size_t leg, std::size_t stops);

struct Route {
  std::vector<Vec3> waypoints;
  double length_m() const;
};

struct PlanStats {
  std::uint64_t nodes_expanded = 0;
  std::uint64_t open_max = 0;    // largest open list seen
  std::uint64_t grid_cells = 0;  // size of the search grid, when there is one
  double cell_m = 0.0;           // horizontal grid resolution used
  double grid_route_m = 0.0;     // a grid search's route before shortcuts (0: none); not in plan files
  double plan_ms = 0.0;
};

// A planner's outcome (message: why it failed, or a note) and its route.
struct PlanResult : Outcome {
  Route route;
  PlanStats stats;
};

}  // namespace uavplan
