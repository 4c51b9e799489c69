#include "uavplan/io/gis_export.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>

#include "uavplan/io/export_common.h"
#include "uavplan/io/palette.h"

namespace uavplan {
namespace {

using ojson = nlohmann::ordered_json;

// True when b lies on the straight way from a on to c (within 1 mm).
bool on_the_way(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, bc = c - b;
  return ab.dot(bc) > 0.0 && ab.cross(bc).norm() <= 1e-3 * (ab.norm() + bc.norm());
}

// The trajectory's corners: holds collapse to one point, rows on a straight leg are left out
// (every vertex is still a trajectory position).
std::vector<Vec3> flown_points(const Trajectory& tr) {
  std::vector<Vec3> pts;
  for (const auto& s : tr) {
    if (!pts.empty() && (s.p - pts.back()).norm() <= kHoldMove_m) continue;
    if (pts.size() >= 2 && on_the_way(pts[pts.size() - 2], pts.back(), s.p))
      pts.back() = s.p;
    else
      pts.push_back(s.p);
  }
  return pts;
}

std::pair<double, double> z_range(const Obstacle& o) {
  const Aabb b = bounding_box(o);
  return {b.min.z(), b.max.z()};
}

ojson lonlatalt(const GeoFrame& f, const Vec3& p) {
  const LatLonAlt g = rounded(f.to_wgs84(p));
  return ojson::array({g.lon_deg, g.lat_deg, g.alt_m});
}

// Whether s[i..] begins U+FFFE or U+FFFF (EF BF BE, EF BF BF), which XML 1.0 excludes from Char.
bool xml_nonchar_at(std::string_view s, std::size_t i) {
  return s.size() - i >= 3 && s[i] == '\xEF' && s[i + 1] == '\xBF' && (s[i + 2] == '\xBE' || s[i + 2] == '\xBF');
}

std::string xml_escape(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (xml_nonchar_at(s, i)) {  // no way to write it in XML 1.0, not even as a reference
      out += "\xEF\xBF\xBD";
      i += 2;
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      // XML 1.0 has no way to write C0 controls but tab, newline and return, not even as
      // references: such a character from a name becomes U+FFFD.
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
          out += "\xEF\xBF\xBD";
        else
          out += c;
    }
  }
  return out;
}

std::string kml_coord(const GeoFrame& f, const Vec3& p) {
  const LatLonAlt g = rounded(f.to_wgs84(p));
  return short_num(g.lon_deg) + "," + short_num(g.lat_deg) + "," + short_num(g.alt_m);
}

const GeoOrigin& origin_of(const Scenario& sc) {
  if (!sc.origin)
    throw ExportError("scenario '" + sc.name + "' has no origin: add origin: {lat, lon, alt} to export to WGS84");
  return *sc.origin;
}

}  // namespace

std::string plan_geojson(const Scenario& sc, const VerifiedExport& flights) {
  const GeoFrame frame(origin_of(sc));
  ojson features = ojson::array();
  for (const ExportedUav& e : flights.uavs) {
    ojson coords = ojson::array();
    for (const Vec3& p : flown_points(exported_rows(e))) coords.push_back(lonlatalt(frame, p));
    if (coords.size() < 2) continue;  // a LineString needs two distinct positions
    features.push_back(ojson{{"type", "Feature"},
                             {"properties",
                              {{"kind", "route"},
                               {"uav", e.spec->id},
                               {"end", to_string(e.end)},
                               {"length_m", e.plan.length_m},
                               {"arrival_s", e.plan.arrival_s}}},
                             {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coords)}}}});
  }
  const auto& obstacles = sc.world.obstacles();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    ojson ring = ojson::array();
    for (const Vec2& v : footprint(obstacles[k])) ring.push_back(lonlatalt(frame, Vec3(v.x(), v.y(), 0.0)));
    ring.push_back(ring.front());  // RFC 7946: closed, counter-clockwise exterior ring
    const auto [lo, hi] = z_range(obstacles[k]);
    features.push_back(ojson{{"type", "Feature"},
                             {"properties",
                              {{"kind", "obstacle"},
                               {"id", obstacle_name(sc.world, k)},
                               {"index", k},
                               {"shape", shape_name(obstacles[k])},
                               {"z_min_m", lo},
                               {"z_max_m", hi}}},
                             {"geometry", {{"type", "Polygon"}, {"coordinates", ojson::array({std::move(ring)})}}}});
  }
  const auto& radars = sc.world.radars();
  for (std::size_t k = 0; k < radars.size(); ++k)
    features.push_back(
        ojson{{"type", "Feature"},
              {"properties",
               {{"kind", "threat"}, {"id", radar_name(sc.world, k)}, {"index", k}, {"weight", radars[k].weight}}},
              {"geometry", {{"type", "Point"}, {"coordinates", lonlatalt(frame, radars[k].position)}}}});
  ojson j{{"type", "FeatureCollection"}, {"name", sc.name}, {"features", std::move(features)}};
  return j.dump(1) + "\n";
}

std::string plan_kml(const Scenario& sc, const VerifiedExport& flights) {
  const GeoFrame frame(origin_of(sc));
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n";
  out += "<name>" + xml_escape(sc.name) + "</name>\n";
  for (std::size_t c = 0; c < kUavPalette.size(); ++c)
    out += "<Style id=\"route" + std::to_string(c) + "\"><LineStyle><color>" + kml_colour(c) +
           "</color><width>3</width></LineStyle></Style>\n";
  out +=
      "<Style "
      "id=\"obstacle\"><LineStyle><color>ff404040</color></LineStyle><PolyStyle><color>80808080</color></PolyStyle></"
      "Style>\n";
  out += "<Folder><name>routes</name>\n";
  for (const ExportedUav& e : flights.uavs) {
    std::size_t colour = 0;  // the UAV's colour in the report: its index in the scenario
    while (colour < sc.uavs.size() && sc.uavs[colour].id != e.spec->id) ++colour;
    const std::vector<Vec3> pts = flown_points(exported_rows(e));
    if (pts.size() < 2) continue;
    out += "<Placemark><name>" + xml_escape(e.spec->id) + "</name><description>end " + std::string(to_string(e.end)) +
           ", length " + short_num(e.plan.length_m) + " m, arrival " + short_num(e.plan.arrival_s) +
           " s</description><styleUrl>#route" + std::to_string(colour % kUavPalette.size()) +
           "</styleUrl>\n<LineString><altitudeMode>absolute</altitudeMode><coordinates>";
    for (std::size_t i = 0; i < pts.size(); ++i) out += (i ? " " : "") + kml_coord(frame, pts[i]);
    out += "</coordinates></LineString></Placemark>\n";
  }
  out += "</Folder>\n<Folder><name>obstacles</name>\n";
  const auto& obstacles = sc.world.obstacles();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const auto [lo, hi] = z_range(obstacles[k]);
    std::vector<Vec2> ring = footprint(obstacles[k]);
    ring.push_back(ring.front());
    out += "<Placemark><name>" + xml_escape(obstacle_name(sc.world, k)) + " (" + std::string(shape_name(obstacles[k])) +
           ", " + short_num(lo) + " to " + short_num(hi) +
           " m)</name><styleUrl>#obstacle</styleUrl>\n<Polygon><extrude>1</extrude><altitudeMode>absolute</"
           "altitudeMode><outerBoundaryIs><LinearRing><coordinates>";
    for (std::size_t i = 0; i < ring.size(); ++i)
      out += (i ? " " : "") + kml_coord(frame, Vec3(ring[i].x(), ring[i].y(), hi));
    out += "</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>\n";
  }
  out += "</Folder>\n</Document>\n</kml>\n";
  return out;
}

std::string trajectory_csv(const Scenario& sc, const ExportedUav& e) {
  std::optional<GeoFrame> frame;
  if (sc.origin) frame.emplace(*sc.origin);
  std::string out = frame ? "t,x,y,z,lat,lon,alt\n" : "t,x,y,z\n";
  for (const auto& s : exported_rows(e)) {
    out += short_num(s.t_s) + "," + short_num(s.p.x()) + "," + short_num(s.p.y()) + "," + short_num(s.p.z());
    if (frame) {
      const LatLonAlt g = rounded(frame->to_wgs84(s.p));
      out += "," + short_num(g.lat_deg) + "," + short_num(g.lon_deg) + "," + short_num(g.alt_m);
    }
    out += "\n";
  }
  return out;
}

}  // namespace uavplan
