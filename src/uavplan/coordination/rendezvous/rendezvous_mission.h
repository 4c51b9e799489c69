// Mission `rendezvous`: P4's simultaneous arrival by route-length control on directional A*
// (rendezvous.h), then departures: all UAVs depart at once and fly at their cruise speed, so
// equal lengths are equal arrival times.
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

class RendezvousMission final : public Mission {
 public:
  std::vector<std::string> algorithms() const override { return {"directional_astar"}; }
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
};

}  // namespace uavplan
