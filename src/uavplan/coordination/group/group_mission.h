// Mission `group`: P3's group planning with the potential field, frame by frame with
// time-stamped peers, then smoothing (group_planner.h).
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

class GroupMission final : public Mission {
 public:
  const MissionDeclaration& declaration() const override {
    static const MissionDeclaration d = [] {
      MissionDeclaration m;
      m.name = "group";
      m.summary =
          "P3's group: each UAV plans in the potential field frame by frame, the others' time-stamped positions "
          "its obstacles, then its path is smoothed; the plan adds P3's path score.";
      m.algorithms = {"apf", "apf_traditional"};
      m.default_algorithm = "apf";
      m.metrics = {"p3_group_score"};
      return m;
    }();
    return d;
  }
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
};

}  // namespace uavplan
