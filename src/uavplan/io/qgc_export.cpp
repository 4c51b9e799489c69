#include "uavplan/io/qgc_export.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/io/export_common.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/mission_items.h"

namespace uavplan {
namespace {

using ojson = nlohmann::ordered_json;

// QGroundControl's altitude modes: 1 relative to home, 2 above sea level, 4 the terrain frame.
int qgc_altitude_mode(int frame) { return frame == kFrameGlobal ? 2 : frame == kFrameGlobalTerrainAlt ? 4 : 1; }

ojson mission_json(const std::vector<MissionItem>& items) {
  ojson out = ojson::array();
  int jump_id = 1;
  for (const MissionItem& it : items) {
    ojson j;
    if (it.positioned()) {
      j["AMSLAltAboveTerrain"] = it.amsl_m;  // a number: QGC's loader rejects null here
      j["Altitude"] = it.params[6];
      j["AltitudeMode"] = qgc_altitude_mode(it.frame);
    }
    j["autoContinue"] = true;
    j["command"] = it.command;
    j["doJumpId"] = jump_id++;
    j["frame"] = it.frame;
    j["params"] = ojson::array();
    for (double p : it.params) j["params"].push_back(p);
    j["type"] = "SimpleItem";
    out.push_back(std::move(j));
  }
  return out;
}

// A zone of the scenario's airspace files, in QGC's fence form, with the corners it was read with.
void append_zone(const FenceZone& z, ojson& polygons, ojson& circles) {
  if (z.polygon_latlon.empty()) {
    circles.push_back(ojson{
        {"circle", {{"center", ojson::array({z.center_latlon.x(), z.center_latlon.y()})}, {"radius", z.radius_m}}},
        {"inclusion", z.inclusion},
        {"version", 1}});
    return;
  }
  ojson poly = ojson::array();
  for (const Vec2& c : z.polygon_latlon) poly.push_back(ojson::array({c.x(), c.y()}));
  polygons.push_back(ojson{{"inclusion", z.inclusion}, {"polygon", std::move(poly)}, {"version", 1}});
}

// Exclusions: the obstacles this UAV can neither over- nor under-fly at the heights its route
// flies (a fence is 2-D: an obstacle the route passes over must not become one; the take-off and
// landing legs reach the ground and do not count), largest first.
ojson fence_json(const Scenario& sc, const ExportedUav& e, const GeoFrame& frame, const ExportOptions& opt,
                 std::vector<std::string>* notes) {
  ojson polygons = ojson::array(), circles = ojson::array();
  if (opt.fence == FenceMode::none) return {{"circles", circles}, {"polygons", polygons}, {"version", 2}};
  const double keep = keep_off_m(*e.spec);
  double z_lo = World::kInf, z_hi = -World::kInf;
  const auto& tr = e.plan.trajectory;
  for (std::size_t k = e.body_begin; k <= e.body_end && k < tr.size(); ++k) {
    z_lo = std::min(z_lo, tr[k].p.z() - keep);
    z_hi = std::max(z_hi, tr[k].p.z() + keep);
  }
  auto latlon = [&](double x, double y) {
    const LatLonAlt g = rounded(frame.to_wgs84(Vec3(x, y, 0.0)));
    return ojson::array({g.lat_deg, g.lon_deg});
  };
  const auto passable = [&](double lo, double hi) { return lo > z_lo || hi < z_hi; };  // flown over or under
  // The scenario's airspace zones as their files gave them (a fence read is the fence written);
  // the world's bounds as the inclusion where no file gave one.
  std::vector<char> from_airspace(sc.world.obstacles().size(), 0);
  bool fenced = false;
  for (const FenceZone& z : sc.airspace) {
    for (const std::size_t k : z.obstacles) from_airspace[k] = 1;
    fenced = fenced || z.inclusion;
    const double floor = z.floor_amsl_m ? *z.floor_amsl_m - frame.origin().alt_m : -World::kInf;
    const double ceiling = z.ceiling_amsl_m ? *z.ceiling_amsl_m - frame.origin().alt_m : World::kInf;
    if (!z.inclusion && passable(floor, ceiling)) continue;
    append_zone(z, polygons, circles);
  }
  const Aabb& b = sc.world.bounds();
  if (!fenced)
    polygons.push_back(ojson{{"inclusion", true},
                             {"polygon", ojson::array({latlon(b.min.x(), b.min.y()), latlon(b.max.x(), b.min.y()),
                                                       latlon(b.max.x(), b.max.y()), latlon(b.min.x(), b.max.y())})},
                             {"version", 1}});
  std::vector<std::pair<double, std::size_t>> walls;  // (footprint area, obstacle)
  const auto& obstacles = sc.world.obstacles();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    if (std::holds_alternative<Sphere>(obstacles[k]) || from_airspace[k]) continue;
    const Aabb ob = bounding_box(obstacles[k]);
    if (passable(ob.min.z(), ob.max.z())) continue;
    walls.emplace_back(std::abs(polygon_signed_area(footprint(obstacles[k]))), k);
  }
  std::stable_sort(walls.begin(), walls.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  const std::size_t keep_n =
      opt.fence == FenceMode::all
          ? walls.size()
          : std::min(walls.size(), static_cast<std::size_t>(std::max(0, opt.max_fence_exclusions)));
  if (notes && keep_n < walls.size())
    notes->push_back("geofence: the " + std::to_string(keep_n) + " largest of " + std::to_string(walls.size()) +
                     " exclusion zones (" + std::to_string(walls.size() - keep_n) +
                     " smaller ones left out: autopilots cap stored fence points; --fence all keeps them)");
  for (std::size_t n = 0; n < keep_n; ++n) {
    const Obstacle& o = obstacles[walls[n].second];
    if (const auto* c = std::get_if<Cylinder>(&o)) {
      circles.push_back(ojson{{"circle", {{"center", latlon(c->center.x(), c->center.y())}, {"radius", c->radius_m}}},
                              {"inclusion", false},
                              {"version", 1}});
      continue;
    }
    ojson poly = ojson::array();
    for (const Vec2& v : footprint(o)) poly.push_back(latlon(v.x(), v.y()));
    polygons.push_back(ojson{{"inclusion", false}, {"polygon", std::move(poly)}, {"version", 1}});
  }
  return {{"circles", std::move(circles)}, {"polygons", std::move(polygons)}, {"version", 2}};
}

// PX4 up to v1.14 refuses a mission whose first waypoint lies more than MIS_DIST_1WP from home
// or with a leg longer than MIS_DIST_WPS (both 900 m by default; PX4 main checks neither): say
// so, naming the parameter, rather than leave the pilot to meet the refusal.
void px4_distance_notes(const GeoFrame& frame, const Vec3& home, const std::vector<MissionItem>& items,
                        std::vector<std::string>* notes) {
  constexpr double kPx4Default_m = 900.0;
  std::optional<Vec2> prev;
  double longest = 0.0;
  for (const MissionItem& it : items) {
    if (!it.positioned() || it.command == kCmdTakeoff) continue;
    // Horizontal distances, as PX4 measures them.
    const Vec2 p = frame.to_local(it.params[4], it.params[5], frame.origin().alt_m).head<2>();
    if (!prev && (p - home.head<2>()).norm() > kPx4Default_m)
      notes->push_back("the first waypoint is " + num_text(std::round((p - home.head<2>()).norm())) +
                       " m from home: PX4 v1.14 refuses it unless MIS_DIST_1WP is raised (default 900 m) or 0");
    if (prev) longest = std::max(longest, (p - *prev).norm());
    prev = p;
  }
  if (longest > kPx4Default_m)
    notes->push_back("a leg of " + num_text(std::round(longest)) +
                     " m: PX4 up to v1.14 refuses legs over MIS_DIST_WPS (default 900 m); raise it or set it to 0");
}

// PX4 up to v1.14 refuses a take-off that climbs less than NAV_ACC_RAD + 1 m above home (11 m
// by default: "Takeoff altitude too low"). The take-off is the verified flight's, so it stays as
// planned (docs/decisions/0022-px4-takeoff-height.md); the note says what to change.
void px4_takeoff_note(const ExportedUav& e, const ExportOptions& opt, std::vector<std::string>* notes) {
  constexpr double kPx4AcceptanceRadius_m = 10.0;  // NAV_ACC_RAD's default
  const double climb_m = e.takeoff_to.z() - e.home.z();
  if (opt.vehicle != VehicleKind::multirotor || climb_m >= kPx4AcceptanceRadius_m + 1.0) return;
  const double radius_m = std::floor((climb_m - 1.0) * 10.0) / 10.0;  // the most that lets it pass
  notes->push_back("the take-off climbs " + num_text(std::round(climb_m * 100.0) / 100.0) +
                   " m above home: PX4 up to v1.14 refuses a take-off below NAV_ACC_RAD + 1 m (11 m by default); " +
                   (radius_m > 0.0 ? "set NAV_ACC_RAD to " + num_text(radius_m) + " m or less, or " : std::string()) +
                   "plan the UAV higher (min_agl 11)");
}

}  // namespace

std::string qgc_plan_json(const Scenario& sc, const ExportedUav& e, const ExportOptions& opt,
                          std::vector<std::string>* notes) {
  const std::vector<MissionItem> items = mission_items(sc, e, opt);
  const GeoFrame frame(*sc.origin);
  const LatLonAlt home = rounded(frame.to_wgs84(e.home));
  const LatLonAlt rally = rounded(frame.to_wgs84(e.takeoff_to));
  ojson j;
  j["fileType"] = "Plan";
  j["geoFence"] = fence_json(sc, e, frame, opt, notes);
  if (notes && opt.firmware == Firmware::px4) {
    px4_distance_notes(frame, e.home, items, notes);
    px4_takeoff_note(e, opt, notes);
  }
  j["groundStation"] = "uavplan";
  j["mission"] = {{"cruiseSpeed", e.spec->speed.cruise_mps},
                  {"firmwareType", opt.firmware == Firmware::px4 ? 12 : 3},
                  {"globalPlanAltitudeMode", 1},
                  {"hoverSpeed", e.spec->speed.cruise_mps},
                  {"items", mission_json(items)},
                  {"plannedHomePosition", ojson::array({home.lat_deg, home.lon_deg, home.alt_m})},
                  {"vehicleType", opt.vehicle == VehicleKind::multirotor ? 2 : 1},
                  {"version", 2}};
  j["rallyPoints"] = {
      {"points", ojson::array({ojson::array({rally.lat_deg, rally.lon_deg, round_m(rally.alt_m - home.alt_m)})})},
      {"version", 2}};
  j["version"] = 1;
  return j.dump(4) + "\n";
}

std::string qgc_wpl(const Scenario& sc, const ExportedUav& e, const ExportOptions& opt) {
  const std::vector<MissionItem> items = mission_items(sc, e, opt);
  const GeoFrame frame(*sc.origin);
  const LatLonAlt home = rounded(frame.to_wgs84(e.home));
  std::string out = "QGC WPL 110\n";
  // Row 0 is home, absolute altitude (frame 0), as QGroundControl and ArduPilot write it.
  out += "0\t1\t0\t16\t0\t0\t0\t0\t" + short_num(home.lat_deg) + "\t" + short_num(home.lon_deg) + "\t" +
         short_num(home.alt_m) + "\t1\n";
  int index = 1;
  for (const MissionItem& it : items) {
    out += std::to_string(index++) + "\t0\t" + std::to_string(it.frame) + "\t" + std::to_string(it.command);
    for (double p : it.params) out += "\t" + short_num(p);
    out += "\t1\n";
  }
  return out;
}

}  // namespace uavplan
