// The rendezvous mission's part of the contract: the tolerance of the route lengths (P4's
// simultaneous arrival), as read and as verified.
#include <algorithm>

#include "uavplan/coordination/rendezvous/rendezvous_mission.h"
#include "uavplan/core/text.h"

namespace uavplan {

const RendezvousSection& rendezvous_section(const Scenario& sc) {
  static const RendezvousSection none;
  const RendezvousSection* s = sc.mission.section_as<RendezvousSection>();
  return s ? *s : none;
}

void RendezvousMission::read_section(const Section& m, const Section& /*uavs*/, Scenario& sc) const {
  RendezvousSection& s = sc.mission.edit_section<RendezvousSection>();
  if (m.has("arrival_tolerance")) s.arrival_tolerance_m = m.at("arrival_tolerance")->positive();
}

std::string RendezvousMission::describe(const Scenario& sc) const {
  return rendezvous_section(sc).arrival_tolerance_m
             ? ", route lengths within " + num_text(*rendezvous_section(sc).arrival_tolerance_m) + " m"
             : "";
}

// The flown lengths of all UAVs within the tolerance of one another.
void RendezvousMission::check_plan(const Scenario& sc, const FlownUavs& flown, Violations& out) const {
  if (!rendezvous_section(sc).arrival_tolerance_m || flown.size() < 2) return;
  double lo = World::kInf, hi = 0.0;
  for (const auto& [u, up] : flown) {
    const double len = flown_length_m(up->trajectory);
    lo = std::min(lo, len);
    hi = std::max(hi, len);
  }
  if (hi - lo > *rendezvous_section(sc).arrival_tolerance_m + kDistanceTolerance_m)
    add_violation(out, ViolationKind::length_spread, "", std::nullopt, std::nullopt,
                  "route lengths differ by " + num_text(hi - lo) + " m, above the tolerance " +
                      num_text(*rendezvous_section(sc).arrival_tolerance_m) + " m");
}

}  // namespace uavplan
