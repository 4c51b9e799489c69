#include "uavplan/coordination/mission.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <utility>

#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/coordination/formation_mission/phased_formation_mission.h"
#include "uavplan/coordination/group/group_mission.h"
#include "uavplan/coordination/rendezvous/rendezvous_mission.h"
#include "uavplan/coordination/routes/routes_mission.h"
#include "uavplan/core/text.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

const std::vector<std::pair<MissionType, std::unique_ptr<Mission>>>& registry() {
  static const auto table = [] {
    std::vector<std::pair<MissionType, std::unique_ptr<Mission>>> t;
    t.emplace_back(MissionType::independent, std::make_unique<RoutesMission>(MissionType::independent));
    t.emplace_back(MissionType::route, std::make_unique<RoutesMission>(MissionType::route));
    t.emplace_back(MissionType::group, std::make_unique<GroupMission>());
    t.emplace_back(MissionType::rendezvous, std::make_unique<RendezvousMission>());
    t.emplace_back(MissionType::formation, std::make_unique<FormationMission>());
    t.emplace_back(MissionType::formation_mission, std::make_unique<PhasedFormationMission>());
    return t;
  }();
  return table;
}

}  // namespace

void Mission::check_pair(const Scenario& /*scenario*/, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                         const Trajectory& tb, double need_m, Violations& out) const {
  const Encounter e = closest_approach(ta, tb);
  if (e.distance_m < need_m - kDistanceTolerance_m)
    add_violation(
        out, ViolationKind::separation, a.id, e.t_s, e.where,
        "distance " + num_text(e.distance_m) + " m to '" + b.id + "', below the separation " + num_text(need_m) + " m");
}

const Mission* find_mission(MissionType type) {
  for (const auto& [t, m] : registry())
    if (t == type) return m.get();
  return nullptr;
}

std::vector<MissionType> mission_types() {
  std::vector<MissionType> types;
  for (const auto& [t, m] : registry()) types.push_back(t);
  return types;
}

std::string mission_type_list() {
  const auto& table = registry();
  std::string list;
  for (std::size_t i = 0; i < table.size(); ++i)
    list += (i == 0 ? "" : i + 1 == table.size() ? " or " : ", ") + std::string(to_string(table[i].first));
  return list;
}

bool route_with_entry_headings(const Scenario& sc) {
  const auto& headings = sc.mission.waypoint_entry_heading_rad;
  return sc.mission.type == MissionType::route &&
         std::any_of(headings.begin(), headings.end(), [](const std::optional<double>& h) { return h.has_value(); });
}

namespace {

// Refuses `asked` where the planner lacks a capability (`has`), naming those that have it.
void require_planner(const std::string& asked, bool PlannerInfo::*has, const std::string& lacks,
                     const std::string& who) {
  for (const PlannerInfo& p : planner_catalog())
    if (p.name == asked && !(p.*has)) {
      std::string why = "'" + asked + "' ";
      why += lacks;
      why += "; ";
      why += who;
      why += " plans with ";
      const std::size_t named = why.size();
      for (const PlannerInfo& q : planner_catalog())
        if (q.*has) (why += why.size() > named ? ", " : "") += q.name;
      throw std::invalid_argument(why);
    }
}

}  // namespace

std::string mission_algorithm(const Scenario& sc, const std::optional<std::string>& asked_cli) {
  const Mission* mission = find_mission(sc.mission.type);
  const std::vector<std::string> allowed = mission ? mission->algorithms() : std::vector<std::string>{};
  const std::optional<std::string> asked = asked_cli ? asked_cli
                                           : sc.planner.algorithm_given
                                               ? std::optional<std::string>(sc.planner.algorithm)
                                               : std::nullopt;
  const std::string type(to_string(sc.mission.type));
  const bool entries = route_with_entry_headings(sc);
  if (!asked) return entries ? std::string("pso_mpc") : mission ? mission->default_algorithm() : std::string("astar");
  if (entries)  // only planners that fly into a via point along its heading
    require_planner(*asked, &PlannerInfo::entry_headings, "does not fly into a via point along its entry_heading_deg",
                    "a route with entry headings");
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), *asked) == allowed.end()) {
    std::string list;
    for (std::size_t i = 0; i < allowed.size(); ++i)
      list += (i ? (i + 1 == allowed.size() ? " or " : ", ") : "") + allowed[i];
    throw std::invalid_argument("a " + type + " mission plans with " + list + ", not '" + *asked + "'");
  }
  if (sc.mission.type == MissionType::route)
    require_planner(*asked, &PlannerInfo::via_points, "does not plan through via points", "a route mission");
  return *asked;
}

}  // namespace uavplan
