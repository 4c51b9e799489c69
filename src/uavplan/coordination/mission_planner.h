// Plans a whole scenario: looks its mission type up in the registry (mission.h), chooses the
// planner, and collects the UAVs' plans into one Plan with its status.
#pragma once

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/mission.h"

namespace uavplan {

// Throws std::invalid_argument for an unknown planner, bad parameters or a malformed problem.
Plan plan_mission(const Scenario& scenario, const MissionOptions& options);

}  // namespace uavplan
