// Missions `independent` and `route`: each UAV's route by the chosen planner (through the via
// points in order for `route`), then the routes are timed so that UAVs keep their separation and
// stay clear of moving obstacles (prioritised departure delays: each UAV in turn takes the
// earliest departure that conflicts with none planned before it). UAVs with a sensor_range know
// moving obstacles and other UAVs only through their sensors: they fly their routes in the
// closed loop with P1's rolling-window replanning (rolling_window.h), after the UAVs without
// sensors are timed (those fly as planned, and the sensing ones see them as moving objects).
// Mission parameters: `local` (improved_rrt, default, or rrt: the local replanner) and
// `window_m` (route ahead checked; default the sensor range); `deconfliction` (auto, default:
// delays, and space and time where delays leave a conflict and that solves more; delays;
// space_time, space_time_routes.h) with its `space_time_method` and `space_time_cell_m`. Take-off and landing legs are part
// of the timed routes; a sensing UAV departs into the loop from its lift-off point once it has
// climbed there.
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

enum class RoutesKind { independent, route };

class RoutesMission final : public Mission {
 public:
  // `independent` or `route` (its via points: `mission.waypoints`, route_rules.cpp).
  explicit RoutesMission(RoutesKind kind);
  const MissionDeclaration& declaration() const override { return declaration_; }
  void read_section(const Section& mission, const Section& uavs, Scenario& scenario) const override;
  std::string describe(const Scenario& scenario) const override;
  // A route's via points need planners that pass them, and with entry headings planners that fly
  // in along them (pso_mpc then by default).
  std::string planner_refusal(const Scenario& scenario, const PlannerInfo& planner) const override;
  std::string default_algorithm(const Scenario& scenario) const override;
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
  void check_uav(const Scenario& scenario, const UavSpec& uav, const Trajectory& trajectory,
                 Violations& out) const override;

 private:
  RoutesKind kind_;
  MissionDeclaration declaration_;
};

// Whether the scenario is a route whose via points require entry headings (pso_mpc plans it).
bool route_with_entry_headings(const Scenario& scenario);

}  // namespace uavplan
