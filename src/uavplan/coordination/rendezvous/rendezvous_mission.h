// Mission `rendezvous`: P4's simultaneous arrival by route-length control on directional A*
// (rendezvous.h), then departures: all UAVs depart at once and fly at their cruise speed, so
// equal lengths are equal arrival times.
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

class RendezvousMission final : public Mission {
 public:
  // `arrival_tolerance`: the largest difference of the route lengths (rendezvous_rules.cpp).
  std::vector<const char*> section_keys() const override { return {"arrival_tolerance"}; }
  void read_section(const Section& mission, const Section& uavs, Scenario& scenario) const override;
  std::vector<std::string> algorithms() const override { return {"directional_astar"}; }
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
  void check_plan(const Scenario& scenario, const FlownUavs& flown, Violations& out) const override;
};

}  // namespace uavplan
