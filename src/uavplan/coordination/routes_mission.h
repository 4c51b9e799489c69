// Missions `independent` and `route`: each UAV's route by the chosen planner (through the via
// points in order for `route`), then the routes are timed so that UAVs keep their separation and
// stay clear of moving obstacles (prioritised departure delays: each UAV in turn takes the
// earliest departure that conflicts with none planned before it).
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

class RoutesMission final : public Mission {
 public:
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
};

}  // namespace uavplan
