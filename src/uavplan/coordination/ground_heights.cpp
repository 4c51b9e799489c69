#include "uavplan/coordination/ground_heights.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "uavplan/coordination/mission.h"
#include "uavplan/core/text.h"

namespace uavplan {
namespace {

constexpr double kLiftMargin_m = 0.05;  // above the body and min_agl, where a take-off ends

std::string column_problem(const Scenario& sc, const UavSpec& u, const Vec3& p, double lift_m) {
  const double keep = keep_off_m(u), ground = sc.world.ground_z(p.x(), p.y());
  const Vec3 foot(p.x(), p.y(), ground), top(p.x(), p.y(), ground + lift_m);
  if (!sc.world.in_bounds(top))
    return "the world is not high enough to lift off there (" + num_text(top.z() - ground) + " m needed)";
  const double c = sc.world.ground_leg_clearance(foot, top, keep, ground);
  if (c >= keep - 1e-6) return {};  // touching the ground it stands on at exactly keep_m above it
  // What it comes near, named where the column is lowest off the ground (a slope's rise beside
  // it, a wall): the body's reach above the foot.
  const std::string what = sc.world.nearest_label(Vec3(p.x(), p.y(), ground + keep));
  return "its vertical column up to " + num_text(top.z() - ground) + " m above the ground comes within " + num_text(c) +
         " m of " + what + " beside it (radius plus clearance " + num_text(keep) + " m)" +
         (what == World::kTerrainLabel
              ? "; the ground rises within the body's reach: a flatter spot or a smaller radius lifts off"
              : "");
}

// The points of the scenario on the ground (take-offs and landings) and in the air (to stay
// above min_agl), with the UAV whose they are.
struct Placed {
  std::vector<std::pair<const UavSpec*, Vec3>> ground, air;
  bool defaulted = false;  // a UAV without min_agl touches the ground
};

Placed placed_points(const Scenario& sc) {
  const World& w = sc.world;
  Placed out;
  const UavSpec* widest = nullptr;
  for (const UavSpec& u : sc.uavs) {
    std::vector<Vec3> pts{u.start};
    if (u.goal) pts.push_back(*u.goal);
    if (u.home) pts.push_back(*u.home);
    for (const Vec3& p : pts) {
      const bool ground = w.on_ground(p);
      (ground ? out.ground : out.air).emplace_back(&u, p);
      out.defaulted = out.defaulted || (ground && !u.min_agl_given);
    }
    if (!widest || keep_off_m(u) > keep_off_m(*widest)) widest = &u;
  }
  for (const Vec3& p : sc.mission.waypoints)
    if (widest) out.air.emplace_back(widest, p);
  return out;
}

}  // namespace

double planning_min_agl_m(const Scenario& sc) {
  double agl = sc.default_min_agl_m;
  for (const UavSpec& u : sc.uavs) agl = std::max(agl, u.min_agl_m);
  return agl;
}

std::optional<double> planning_max_agl_m(const Scenario& sc) {
  std::optional<double> agl;
  for (const UavSpec& u : sc.uavs)
    if (u.max_agl_m) agl = std::min(agl.value_or(*u.max_agl_m), *u.max_agl_m);
  return agl;
}

namespace {

// Whether the scenario's mission starts and ends its UAVs on its own ground (an airfield).
bool own_ground(const Scenario& sc) {
  const Mission* mission = find_mission(sc.mission.type);
  return mission && mission->declaration().own_ground;
}

}  // namespace

double default_min_agl_m(const Scenario& sc) {
  const World& w = sc.world;
  if (w.bounds().extent().z() <= 0.0 || own_ground(sc)) return 0.0;
  const Placed placed = placed_points(sc);
  // The fleet's cruise height when the scenario asks for one, else the default where a UAV
  // without min_agl takes off or lands; either gives way to the scenario's room below.
  const std::optional<double> cruise = sc.mission.cruise_agl_m;
  if (!placed.defaulted && !cruise) return 0.0;
  double agl = cruise.value_or(kDefaultMinAgl_m);
  for (const auto& [u, p] : placed.air) {
    // The ground within the body's reach counts, not only the cell under it: on a slope the
    // cell beside a point in the air is higher, and the planners keep the body off it raised.
    const double keep = keep_off_m(*u);
    const TerrainGrid* t = w.terrain();
    const bool over_grid = t && std::isfinite(t->height_at(p.x(), p.y()));  // beside it: the floor
    const double room = over_grid ? p.z() - std::max(w.ground_z(p.x(), p.y()), t->highest_near(p.head<2>(), keep))
                                  : w.lowest_height_above_ground(p, p);
    agl = std::min(agl, room - keep - kLiftMargin_m);
  }
  for (const auto& [u, p] : placed.ground) {
    const double roof = std::min(w.bounds().max.z(), u->ceiling_m.value_or(w.bounds().max.z()));
    agl = std::min(agl, roof - w.ground_z(p.x(), p.y()) - keep_off_m(*u) - 2 * kLiftMargin_m);
  }
  if (const auto top = planning_max_agl_m(sc))  // room for the body in the band
    for (const UavSpec& u : sc.uavs) agl = std::min(agl, *top - 2 * keep_off_m(u) - 2 * kLiftMargin_m);
  if (agl <= 0.0) return 0.0;
  for (const auto& [u, p] : placed.ground)  // a column clear to the old height but not the new: none
    if (column_problem(sc, *u, p, agl + keep_off_m(*u) + kLiftMargin_m).empty() !=
        column_problem(sc, *u, p, planning_min_agl_m(sc) + keep_off_m(*u) + kLiftMargin_m).empty())
      return 0.0;
  return agl;
}

double lift_height_m(const Scenario& sc, const UavSpec& u) {
  return planning_min_agl_m(sc) + keep_off_m(u) + kLiftMargin_m;
}

std::string ground_column_problem(const Scenario& sc, const UavSpec& u, const Vec3& p) {
  return column_problem(sc, u, p, lift_height_m(sc, u));
}

std::string vertical_column_problem(const Scenario& sc, const UavSpec& u, const Vec3& p, double lift_m) {
  return column_problem(sc, u, p, lift_m);
}

}  // namespace uavplan
