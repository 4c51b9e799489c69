#include "uavplan/io/export.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <nlohmann/json.hpp>

#include "uavplan/core/geometry.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/palette.h"

namespace uavplan {
namespace {

using ojson = nlohmann::ordered_json;

constexpr double kHoldMove_m = 1e-6;       // a leg shorter than this is the UAV holding still
constexpr double kCollinearCos = 1.0 - 1e-9;  // legs this parallel are one straight leg
constexpr int kCircleVertices = 64;        // cylinders and spheres as polygons

// Written precision: 1e-9 degrees (0.1 mm on the ground) and 0.1 mm, so files stay readable
// and identical across platforms while keeping far below any autopilot's resolution.
double round_deg(double v) { return std::round(v * 1e9) / 1e9; }
double round_m(double v) { return std::round(v * 1e4) / 1e4; }

LatLonAlt rounded(LatLonAlt g) { return {round_deg(g.lat_deg), round_deg(g.lon_deg), round_m(g.alt_m)}; }

std::string num(double v) {
  if (v == 0.0) return "0";  // also folds -0
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

const UavSpec& spec_of(const Scenario& sc, const UavPlan& u) {
  const UavSpec* s = sc.find_uav(u.id);
  if (!s) throw ExportError("plan UAV '" + u.id + "' is not in scenario '" + sc.name + "'");
  return *s;
}

const GeoOrigin& origin_of(const Scenario& sc) {
  if (!sc.origin)
    throw ExportError("scenario '" + sc.name + "' has no origin: add origin: {lat, lon, alt} to export to WGS84");
  return *sc.origin;
}

double ground_z(const Scenario& sc, const Vec3& p) {
  const TerrainGrid* t = sc.world.terrain();
  const double h = t ? t->height_at(p.x(), p.y()) : 0.0;
  return std::isfinite(h) ? std::max(h, 0.0) : 0.0;
}

// Compass yaw (0 = north, clockwise) of a horizontal direction, degrees in [0, 360).
double compass_yaw_deg(const Vec3& d) {
  if (std::hypot(d.x(), d.y()) < 1e-12) return 0.0;
  double yaw = std::atan2(d.x(), d.y()) * 180.0 / std::numbers::pi;
  if (yaw < 0.0) yaw += 360.0;
  return yaw;
}

// Horizontal footprint of an obstacle, counter-clockwise, not closed.
std::vector<Vec2> footprint(const Obstacle& o) {
  std::vector<Vec2> ring;
  auto circle = [&](const Vec2& c, double r) {
    for (int k = 0; k < kCircleVertices; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kCircleVertices;
      ring.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
    }
  };
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          circle(Vec2(s.center.x(), s.center.y()), s.radius_m);
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          circle(s.center, s.radius_m);
        } else if constexpr (std::is_same_v<T, Box>) {
          ring = {{s.min.x(), s.min.y()}, {s.max.x(), s.min.y()}, {s.max.x(), s.max.y()}, {s.min.x(), s.max.y()}};
        } else {
          ring = s.polygon;
          double area2 = 0.0;
          for (std::size_t i = 0; i < ring.size(); ++i) {
            const Vec2& a = ring[i];
            const Vec2& b = ring[(i + 1) % ring.size()];
            area2 += a.x() * b.y() - b.x() * a.y();
          }
          if (area2 < 0.0) std::reverse(ring.begin(), ring.end());
        }
      },
      o);
  return ring;
}

std::string_view shape_name(const Obstacle& o) {
  static constexpr std::string_view names[] = {"sphere", "cylinder", "box", "prism"};
  return names[o.index()];
}

std::pair<double, double> z_range(const Obstacle& o) {
  const Aabb b = bounding_box(o);
  return {b.min.z(), b.max.z()};
}

// Positions of the trajectory without repeats (holds collapse to one point).
std::vector<Vec3> flown_points(const UavPlan& u) {
  std::vector<Vec3> pts;
  for (const auto& s : u.trajectory)
    if (pts.empty() || (s.p - pts.back()).norm() > kHoldMove_m) pts.push_back(s.p);
  return pts;
}

ojson lonlatalt(const GeoFrame& f, const Vec3& p) {
  const LatLonAlt g = rounded(f.to_wgs84(p));
  return ojson::array({g.lon_deg, g.lat_deg, g.alt_m});
}

bool exportable(const UavPlan& u) { return u.trajectory.size() >= 2; }

}  // namespace

std::optional<ExportFormat> export_format_from_string(std::string_view s) {
  for (ExportFormat f : {ExportFormat::qgc, ExportFormat::wpl, ExportFormat::geojson, ExportFormat::kml, ExportFormat::csv})
    if (to_string(f) == s) return f;
  return std::nullopt;
}

std::string_view to_string(ExportFormat f) {
  switch (f) {
    case ExportFormat::qgc: return "qgc";
    case ExportFormat::wpl: return "wpl";
    case ExportFormat::geojson: return "geojson";
    case ExportFormat::kml: return "kml";
    case ExportFormat::csv: return "csv";
  }
  return "?";
}

std::string file_stem(std::string_view id) {
  std::string s(id);
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  if (s.empty() || s[0] == '.') s.insert(s.begin(), '_');
  return s;
}

std::vector<MissionItem> mission_items(const Scenario& sc, const UavPlan& uav, const ExportOptions& opt) {
  const UavSpec& spec = spec_of(sc, uav);
  const GeoFrame frame(origin_of(sc));
  const Trajectory& tr = uav.trajectory;
  if (tr.size() < 2) throw ExportError("UAV '" + uav.id + "' has no trajectory to export");
  const double home_amsl = frame.to_wgs84(Vec3(tr.front().p.x(), tr.front().p.y(), ground_z(sc, tr.front().p))).alt_m;

  std::vector<MissionItem> items;
  auto at = [&](int command, const Vec3& p, std::array<double, 4> head) {
    const LatLonAlt g = frame.to_wgs84(p);
    MissionItem it;
    it.command = command;
    it.params = {round_m(head[0]), round_m(head[1]), round_m(head[2]), round_m(head[3]),
                 round_deg(g.lat_deg), round_deg(g.lon_deg), round_m(g.alt_m - home_amsl)};
    items.push_back(it);
  };

  // Takeoff to the start's altitude (or the first higher point when the start is on the ground).
  Vec3 takeoff = tr.front().p;
  const double min_takeoff_m = 1.0;
  if (takeoff.z() - ground_z(sc, takeoff) < min_takeoff_m)
    for (const auto& s : tr)
      if (s.p.z() - ground_z(sc, takeoff) >= min_takeoff_m) {
        takeoff.z() = s.p.z();
        break;
      }
  at(kCmdTakeoff, takeoff, {0, 0, 0, compass_yaw_deg(tr.back().p - tr.front().p)});

  double mission_speed = spec.speed.cruise_mps;
  std::size_t i = 0;
  const std::size_t n = tr.size();
  while (i + 1 < n) {
    const Vec3 a = tr[i].p;
    const double dt = tr[i + 1].t_s - tr[i].t_s;
    if ((tr[i + 1].p - a).norm() <= kHoldMove_m) {
      double hold_s = 0.0;  // consecutive holds are one loiter
      while (i + 1 < n && (tr[i + 1].p - tr[i].p).norm() <= kHoldMove_m) {
        hold_s += tr[i + 1].t_s - tr[i].t_s;
        ++i;
      }
      if (hold_s > 0.0) at(kCmdLoiterTime, a, {hold_s, 0, 0, 0});
      continue;
    }
    // One straight leg at one speed, as long as the following legs keep direction and speed.
    const Vec3 dir = (tr[i + 1].p - a).normalized();
    const double speed = (tr[i + 1].p - a).norm() / std::max(dt, 1e-12);
    std::size_t j = i + 1;
    while (j + 1 < n) {
      const Vec3 d = tr[j + 1].p - tr[j].p;
      const double len = d.norm();
      if (len <= kHoldMove_m) break;
      const double v = len / std::max(tr[j + 1].t_s - tr[j].t_s, 1e-12);
      if (d.dot(dir) / len < kCollinearCos || std::abs(v - speed) > opt.speed_change_fraction * speed) break;
      ++j;
    }
    if (std::abs(speed - mission_speed) > opt.speed_change_fraction * mission_speed) {
      MissionItem sp;
      sp.command = kCmdChangeSpeed;
      sp.params = {1.0, round_m(speed), -1.0, 0, 0, 0, 0};  // ground speed, m/s, throttle unchanged
      items.push_back(sp);
      mission_speed = speed;
    }
    at(kCmdWaypoint, tr[j].p, {0, 0, 0, compass_yaw_deg(dir)});
    i = j;
  }

  const Vec3 last = tr.back().p;
  if (opt.end == MissionEnd::land) {
    at(kCmdLand, Vec3(last.x(), last.y(), ground_z(sc, last)), {0, 0, 0, 0});
  } else if (opt.end == MissionEnd::rtl) {
    MissionItem rtl;
    rtl.command = kCmdReturn;
    items.push_back(rtl);
  }
  return items;
}

std::string qgc_plan_json(const Scenario& sc, const UavPlan& uav, const ExportOptions& opt) {
  const UavSpec& spec = spec_of(sc, uav);
  const GeoFrame frame(origin_of(sc));
  const std::vector<MissionItem> items = mission_items(sc, uav, opt);
  const Vec3 start = uav.trajectory.front().p;
  const LatLonAlt home = rounded(frame.to_wgs84(Vec3(start.x(), start.y(), ground_z(sc, start))));

  ojson jitems = ojson::array();
  int jump_id = 1;
  double alt_rel = items.front().params[6];
  for (const MissionItem& it : items) {
    const bool positioned = it.command != kCmdChangeSpeed && it.command != kCmdReturn;
    if (positioned) alt_rel = it.params[6];
    ojson j;
    j["AMSLAltAboveTerrain"] = round_m(home.alt_m + alt_rel);  // a number: QGC's loader rejects null here
    j["Altitude"] = alt_rel;
    j["AltitudeMode"] = 1;  // relative to home
    j["autoContinue"] = true;
    j["command"] = it.command;
    j["doJumpId"] = jump_id++;
    j["frame"] = it.frame;
    j["params"] = ojson::array();
    for (double p : it.params) j["params"].push_back(p);
    j["type"] = "SimpleItem";
    jitems.push_back(std::move(j));
  }

  // Fence: the world's bounds as the inclusion polygon; as exclusions, the obstacles this UAV can
  // neither over- nor under-fly at the heights it flies (a fence is 2-D: an obstacle the route
  // passes over must not become one).
  double z_lo = World::kInf, z_hi = -World::kInf;
  for (const auto& s : uav.trajectory) {
    z_lo = std::min(z_lo, s.p.z() - spec.radius_m);
    z_hi = std::max(z_hi, s.p.z() + spec.radius_m);
  }
  auto latlon = [&](double x, double y) {
    const LatLonAlt g = rounded(frame.to_wgs84(Vec3(x, y, 0.0)));
    return ojson::array({g.lat_deg, g.lon_deg});
  };
  ojson polygons = ojson::array(), circles = ojson::array();
  const Aabb& b = sc.world.bounds();
  ojson incl = ojson::array({latlon(b.min.x(), b.min.y()), latlon(b.max.x(), b.min.y()),
                             latlon(b.max.x(), b.max.y()), latlon(b.min.x(), b.max.y())});
  polygons.push_back(ojson{{"inclusion", true}, {"polygon", std::move(incl)}, {"version", 1}});
  for (const Obstacle& o : sc.world.obstacles()) {
    if (std::holds_alternative<Sphere>(o)) continue;
    const auto [lo, hi] = z_range(o);
    if (lo > z_lo || hi < z_hi) continue;
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

  const LatLonAlt rally = rounded(frame.to_wgs84(start));
  ojson j;
  j["fileType"] = "Plan";
  j["geoFence"] = {{"circles", std::move(circles)}, {"polygons", std::move(polygons)}, {"version", 2}};
  j["groundStation"] = "uavplan";
  j["mission"] = {{"cruiseSpeed", spec.speed.cruise_mps},
                  {"firmwareType", opt.firmware == Firmware::px4 ? 12 : 3},
                  {"globalPlanAltitudeMode", 1},
                  {"hoverSpeed", spec.speed.cruise_mps},
                  {"items", std::move(jitems)},
                  {"plannedHomePosition", ojson::array({home.lat_deg, home.lon_deg, home.alt_m})},
                  {"vehicleType", opt.vehicle == VehicleKind::multirotor ? 2 : 1},
                  {"version", 2}};
  j["rallyPoints"] = {{"points", ojson::array({ojson::array({rally.lat_deg, rally.lon_deg, round_m(rally.alt_m - home.alt_m)})})},
                      {"version", 2}};
  j["version"] = 1;
  return j.dump(4) + "\n";
}

std::string qgc_wpl(const Scenario& sc, const UavPlan& uav, const ExportOptions& opt) {
  const GeoFrame frame(origin_of(sc));
  const std::vector<MissionItem> items = mission_items(sc, uav, opt);
  const Vec3 start = uav.trajectory.front().p;
  const LatLonAlt home = rounded(frame.to_wgs84(Vec3(start.x(), start.y(), ground_z(sc, start))));
  std::string out = "QGC WPL 110\n";
  // Row 0 is home, absolute altitude (frame 0), as QGroundControl and ArduPilot write it.
  out += "0\t1\t0\t16\t0\t0\t0\t0\t" + num(home.lat_deg) + "\t" + num(home.lon_deg) + "\t" + num(home.alt_m) + "\t1\n";
  int index = 1;
  for (const MissionItem& it : items) {
    out += std::to_string(index++) + "\t0\t" + std::to_string(it.frame) + "\t" + std::to_string(it.command);
    for (double p : it.params) out += "\t" + num(p);
    out += "\t1\n";
  }
  return out;
}

std::string plan_geojson(const Scenario& sc, const Plan& plan) {
  const GeoFrame frame(origin_of(sc));
  ojson features = ojson::array();
  for (const UavPlan& u : plan.uavs) {
    if (!exportable(u)) continue;
    spec_of(sc, u);
    ojson coords = ojson::array();
    for (const Vec3& p : flown_points(u)) coords.push_back(lonlatalt(frame, p));
    if (coords.size() < 2) continue;  // a LineString needs two distinct positions
    features.push_back(ojson{{"type", "Feature"},
                             {"properties",
                              {{"kind", "route"},
                               {"uav", u.id},
                               {"status", to_string(u.status)},
                               {"length_m", u.length_m},
                               {"arrival_s", u.arrival_s}}},
                             {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coords)}}}});
  }
  int k = 0;
  for (const Obstacle& o : sc.world.obstacles()) {
    ojson ring = ojson::array();
    for (const Vec2& v : footprint(o)) ring.push_back(lonlatalt(frame, Vec3(v.x(), v.y(), 0.0)));
    ring.push_back(ring.front());  // RFC 7946: closed, counter-clockwise exterior ring
    const auto [lo, hi] = z_range(o);
    features.push_back(ojson{{"type", "Feature"},
                             {"properties", {{"kind", "obstacle"}, {"index", k++}, {"shape", shape_name(o)}, {"z_min_m", lo}, {"z_max_m", hi}}},
                             {"geometry", {{"type", "Polygon"}, {"coordinates", ojson::array({std::move(ring)})}}}});
  }
  k = 0;
  for (const Radar& r : sc.world.radars())
    features.push_back(ojson{{"type", "Feature"},
                             {"properties", {{"kind", "threat"}, {"index", k++}, {"weight", r.weight}}},
                             {"geometry", {{"type", "Point"}, {"coordinates", lonlatalt(frame, r.position)}}}});
  ojson j{{"type", "FeatureCollection"}, {"name", sc.name}, {"features", std::move(features)}};
  return j.dump(1) + "\n";
}

namespace {

std::string xml_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string kml_coord(const GeoFrame& f, const Vec3& p) {
  const LatLonAlt g = rounded(f.to_wgs84(p));
  return num(g.lon_deg) + "," + num(g.lat_deg) + "," + num(g.alt_m);
}

}  // namespace

std::string plan_kml(const Scenario& sc, const Plan& plan) {
  const GeoFrame frame(origin_of(sc));
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n";
  out += "<name>" + xml_escape(sc.name) + "</name>\n";
  for (std::size_t c = 0; c < kUavPalette.size(); ++c)
    out += "<Style id=\"route" + std::to_string(c) + "\"><LineStyle><color>" + kml_colour(c) +
           "</color><width>3</width></LineStyle></Style>\n";
  out += "<Style id=\"obstacle\"><LineStyle><color>ff404040</color></LineStyle><PolyStyle><color>80808080</color></PolyStyle></Style>\n";
  out += "<Folder><name>routes</name>\n";
  std::size_t idx = 0;
  for (const UavPlan& u : plan.uavs) {
    const std::size_t colour = idx++ % kUavPalette.size();
    if (!exportable(u)) continue;
    spec_of(sc, u);
    const std::vector<Vec3> pts = flown_points(u);
    if (pts.size() < 2) continue;
    out += "<Placemark><name>" + xml_escape(u.id) + "</name><description>status " + std::string(to_string(u.status)) +
           ", length " + num(u.length_m) + " m, arrival " + num(u.arrival_s) + " s</description><styleUrl>#route" +
           std::to_string(colour) + "</styleUrl>\n<LineString><altitudeMode>absolute</altitudeMode><coordinates>";
    for (std::size_t i = 0; i < pts.size(); ++i) out += (i ? " " : "") + kml_coord(frame, pts[i]);
    out += "</coordinates></LineString></Placemark>\n";
  }
  out += "</Folder>\n<Folder><name>obstacles</name>\n";
  int k = 0;
  for (const Obstacle& o : sc.world.obstacles()) {
    const auto [lo, hi] = z_range(o);
    std::vector<Vec2> ring = footprint(o);
    ring.push_back(ring.front());
    out += "<Placemark><name>obstacle " + std::to_string(k++) + " (" + std::string(shape_name(o)) + ", " + num(lo) +
           " to " + num(hi) + " m)</name><styleUrl>#obstacle</styleUrl>\n<Polygon><extrude>1</extrude><altitudeMode>absolute</altitudeMode><outerBoundaryIs><LinearRing><coordinates>";
    for (std::size_t i = 0; i < ring.size(); ++i) out += (i ? " " : "") + kml_coord(frame, Vec3(ring[i].x(), ring[i].y(), hi));
    out += "</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>\n";
  }
  out += "</Folder>\n</Document>\n</kml>\n";
  return out;
}

std::string trajectory_csv(const Scenario& sc, const UavPlan& uav) {
  // Local coordinates always; WGS84 columns when the scenario has an origin.
  std::optional<GeoFrame> frame;
  if (sc.origin) frame.emplace(*sc.origin);
  std::string out = frame ? "t,x,y,z,lat,lon,alt\n" : "t,x,y,z\n";
  for (const auto& s : uav.trajectory) {
    out += num(s.t_s) + "," + num(s.p.x()) + "," + num(s.p.y()) + "," + num(s.p.z());
    if (frame) {
      const LatLonAlt g = rounded(frame->to_wgs84(s.p));
      out += "," + num(g.lat_deg) + "," + num(g.lon_deg) + "," + num(g.alt_m);
    }
    out += "\n";
  }
  return out;
}

bool needs_origin(ExportFormat f) { return f != ExportFormat::csv; }

std::vector<ExportFile> export_plan(const Scenario& sc, const Plan& plan, ExportFormat format, const ExportOptions& opt) {
  if (needs_origin(format)) origin_of(sc);
  std::vector<ExportFile> files;
  switch (format) {
    case ExportFormat::geojson: files.push_back({"plan.geojson", plan_geojson(sc, plan)}); break;
    case ExportFormat::kml: files.push_back({"plan.kml", plan_kml(sc, plan)}); break;
    default: {
      std::vector<std::string> used;
      for (const UavPlan& u : plan.uavs) {
        if (!exportable(u)) continue;
        std::string stem = file_stem(u.id);
        if (std::find(used.begin(), used.end(), stem) != used.end()) stem += "_" + std::to_string(used.size());
        used.push_back(stem);
        if (format == ExportFormat::qgc) files.push_back({stem + ".plan", qgc_plan_json(sc, u, opt)});
        if (format == ExportFormat::wpl) files.push_back({stem + ".waypoints", qgc_wpl(sc, u, opt)});
        if (format == ExportFormat::csv) files.push_back({stem + ".csv", trajectory_csv(sc, u)});
      }
    }
  }
  return files;
}

}  // namespace uavplan
