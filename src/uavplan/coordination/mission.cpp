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

namespace uavplan {
namespace {

// The built-in missions first, then those registered by register_mission. Registration happens
// before main (static objects) or before planning starts; lookups only read.
std::vector<std::unique_ptr<const Mission>>& registry() {
  static std::vector<std::unique_ptr<const Mission>> table = [] {
    std::vector<std::unique_ptr<const Mission>> t;
    t.push_back(std::make_unique<RoutesMission>(RoutesKind::independent));
    t.push_back(std::make_unique<RoutesMission>(RoutesKind::route));
    t.push_back(std::make_unique<GroupMission>());
    t.push_back(std::make_unique<RendezvousMission>());
    t.push_back(std::make_unique<FormationMission>());
    t.push_back(std::make_unique<PhasedFormationMission>());
    return t;
  }();
  return table;
}

bool is_type_name(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(),
                                   [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

}  // namespace

const std::vector<MissionKey>& common_mission_keys() {
  const MissionSpec defaults;
  static const std::vector<MissionKey> keys = {
      {"type", "text", defaults.type, "", "the mission type: one of the types below"},
      {"separation", "number", num_text(defaults.separation_m), "m",
       "the least distance between any two UAVs at any time"},
      {"step_s", "number", num_text(defaults.step_s), "s", "the sensing and control period of flights in the loop"},
      {"goal_spacing", "number", "the separation", "m",
       "UAVs whose goals lie closer than this arrive at distinct points this far apart"},
      {"cruise_agl", "number", "2.5 where a UAV takes off or lands", "m",
       "the height above the ground planners keep the fleet at between take-off and landing (a preference: less "
       "where the scenario has less room; the verifier checks min_agl)"},
  };
  return keys;
}

void register_mission(std::unique_ptr<const Mission> mission) {
  const MissionDeclaration& d = mission->declaration();
  if (!is_type_name(d.name)) throw std::invalid_argument("mission type '" + d.name + "': not a name of [a-z0-9_]");
  if (find_mission(d.name)) throw std::invalid_argument("mission type '" + d.name + "' is registered already");
  std::vector<std::string> seen;
  for (const MissionKey& k : common_mission_keys()) seen.push_back(k.key);
  for (const MissionKey& k : d.keys) {
    if (std::find(seen.begin(), seen.end(), k.key) != seen.end())
      throw std::invalid_argument("mission type '" + d.name + "': key '" + k.key + "' declared twice");
    seen.push_back(k.key);
  }
  registry().push_back(std::move(mission));
}

void Mission::check_pair(const Scenario& /*scenario*/, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                         const Trajectory& tb, double need_m, Violations& out) const {
  const Encounter e = closest_approach(ta, tb);
  if (e.distance_m < need_m - kDistanceTolerance_m)
    add_violation(
        out, ViolationKind::separation, a.id, e.t_s, e.where,
        "distance " + num_text(e.distance_m) + " m to '" + b.id + "', below the separation " + num_text(need_m) + " m");
}

const Mission* find_mission(std::string_view type) {
  for (const auto& m : registry())
    if (m->declaration().name == type) return m.get();
  return nullptr;
}

std::vector<const Mission*> missions() {
  std::vector<const Mission*> out;
  for (const auto& m : registry()) out.push_back(m.get());
  return out;
}

std::string mission_type_list() {
  std::vector<std::string> names;
  for (const auto& m : registry()) names.push_back(m->declaration().name);
  return word_list(names);
}

std::string planner_refusal(const Scenario& sc, const PlannerInfo& planner) {
  const Mission* mission = find_mission(sc.mission.type);
  if (!mission) return "no mission type '" + sc.mission.type + "' is registered";
  const std::vector<std::string>& allowed = mission->declaration().algorithms;
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), planner.name) == allowed.end())
    return "a " + sc.mission.type + " mission plans with " + word_list(allowed) + ", not '" + planner.name + "'";
  return mission->planner_refusal(sc, planner);
}

std::string mission_algorithm(const Scenario& sc, const std::optional<std::string>& asked_cli) {
  const Mission* mission = find_mission(sc.mission.type);
  if (!mission) throw std::invalid_argument("no mission type '" + sc.mission.type + "' is registered");
  const std::optional<std::string> asked = asked_cli ? asked_cli
                                           : sc.planner.algorithm_given
                                               ? std::optional<std::string>(sc.planner.algorithm)
                                               : std::nullopt;
  if (!asked) return mission->default_algorithm(sc);
  for (const PlannerInfo& p : planner_catalog()) {
    if (p.name != *asked) continue;
    const std::string why = planner_refusal(sc, p);
    if (why.empty()) return *asked;
    const std::vector<std::string>& declared = mission->declaration().algorithms;
    if (!declared.empty() && std::find(declared.begin(), declared.end(), p.name) == declared.end())
      throw std::invalid_argument(why);  // it names the planners already
    std::vector<std::string> able;
    for (const PlannerInfo& q : planner_catalog())
      if (planner_refusal(sc, q).empty()) able.push_back(q.name);
    throw std::invalid_argument(why + (able.empty() ? "" : "; it plans with " + word_list(able)));
  }
  return *asked;  // an unknown name: make_planner says so, listing the planners
}

std::string mission_catalog_text(bool markdown) {
  std::string out;
  const auto row = [&](const MissionKey& k) {
    const std::string dflt = k.default_value.empty() ? "required" : k.default_value;
    if (markdown)
      out += "| `" + k.key + "` | " + k.type + " | " + dflt + " | " + (k.unit.empty() ? "-" : k.unit) + " | " + k.doc +
             " |\n";
    else
      out +=
          "    " + k.key + " (" + k.type + (k.unit.empty() ? "" : ", " + k.unit) + "; " + dflt + "): " + k.doc + "\n";
  };
  const auto header = [&] {
    if (markdown) out += "| key | type | default | unit | meaning |\n|---|---|---|---|---|\n";
  };
  out += markdown ? "Every mission type reads these keys of `mission`:\n\n" : "every mission type:\n";
  header();
  for (const MissionKey& k : common_mission_keys()) row(k);
  for (const Mission* m : missions()) {
    const MissionDeclaration& d = m->declaration();
    const std::string planners =
        d.algorithms.empty() ? "any planner, " + d.default_algorithm + " by default" : word_list(d.algorithms);
    if (markdown) {
      out += "\n**`" + d.name + "`**: " + d.summary + " Plans with " + planners + ".";
      if (!d.parameters.empty()) out += " Reads " + word_list(d.parameters) + " of `planner.params` itself.";
      out += d.keys.empty() ? " No keys of its own.\n" : "\n\n";
      if (!d.keys.empty()) header();
    } else {
      out += d.name + ": " + d.summary + "\n  plans with " + planners + "\n";
      if (!d.parameters.empty()) out += "  reads planner.params " + word_list(d.parameters) + "\n";
    }
    for (const MissionKey& k : d.keys) row(k);
  }
  return out;
}

}  // namespace uavplan
