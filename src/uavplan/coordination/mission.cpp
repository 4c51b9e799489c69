#include "uavplan/coordination/mission.h"

#include <memory>
#include <utility>

#include "uavplan/coordination/group_mission.h"
#include "uavplan/coordination/rendezvous_mission.h"
#include "uavplan/coordination/routes_mission.h"

namespace uavplan {
namespace {

const std::vector<std::pair<MissionType, std::unique_ptr<Mission>>>& registry() {
  static const auto table = [] {
    std::vector<std::pair<MissionType, std::unique_ptr<Mission>>> t;
    t.emplace_back(MissionType::independent, std::make_unique<RoutesMission>());
    t.emplace_back(MissionType::route, std::make_unique<RoutesMission>());
    t.emplace_back(MissionType::group, std::make_unique<GroupMission>());
    t.emplace_back(MissionType::rendezvous, std::make_unique<RendezvousMission>());
    return t;
  }();
  return table;
}

}  // namespace

const Mission* find_mission(MissionType type) {
  for (const auto& [t, m] : registry())
    if (t == type) return m.get();
  return nullptr;
}

}  // namespace uavplan
