// Mission `rendezvous`: P4's simultaneous arrival by route-length control on directional A*
// (rendezvous.h), then departures: all UAVs depart at once and fly at their cruise speed, so
// equal lengths are equal arrival times.
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

// Its section: the largest difference of the UAVs' flown lengths (none: the lattice's cell).
struct RendezvousSection : MissionSection {
  std::optional<double> arrival_tolerance_m;
};
// The scenario's rendezvous section (an empty one where it has none).
const RendezvousSection& rendezvous_section(const Scenario& scenario);

class RendezvousMission final : public Mission {
 public:
  const MissionDeclaration& declaration() const override {
    static const MissionDeclaration d = [] {
      MissionDeclaration m;
      m.name = "rendezvous";
      m.summary =
          "P4's simultaneous arrival: directional A* routes brought to one length (multi-step search, loiter "
          "circle, virtual threat); all UAVs depart at once at their cruise speed.";
      m.keys = {{"arrival_tolerance", "number", "none", "m", "the largest difference of the UAVs' flown lengths"}};
      m.algorithms = {"directional_astar"};
      m.default_algorithm = "directional_astar";
      return m;
    }();
    return d;
  }
  // `arrival_tolerance` (rendezvous_rules.cpp).
  void read_section(const Section& mission, const Section& uavs, Scenario& scenario) const override;
  std::string describe(const Scenario& scenario) const override;
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
  void check_plan(const Scenario& scenario, const FlownUavs& flown, Violations& out) const override;
};

}  // namespace uavplan
