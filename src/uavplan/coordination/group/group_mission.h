// Mission `group`: P3's group planning with the potential field, frame by frame with
// time-stamped peers, then smoothing (group_planner.h).
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

class GroupMission final : public Mission {
 public:
  std::vector<std::string> algorithms() const override { return {"apf", "apf_traditional"}; }
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
};

}  // namespace uavplan
