#include "uavplan/coordination/contract/scenario.h"

namespace uavplan {

std::string_view to_string(MissionType t) {
  switch (t) {
    case MissionType::independent:
      return "independent";
    case MissionType::route:
      return "route";
    case MissionType::group:
      return "group";
    case MissionType::rendezvous:
      return "rendezvous";
    case MissionType::formation:
      return "formation";
    case MissionType::formation_mission:
      return "formation_mission";
  }
  return "independent";
}

std::optional<MissionType> mission_type_from_string(std::string_view s) {
  for (MissionType t : {MissionType::independent, MissionType::route, MissionType::group, MissionType::rendezvous,
                        MissionType::formation, MissionType::formation_mission})
    if (to_string(t) == s) return t;
  return std::nullopt;
}

}  // namespace uavplan
