#include "uavplan/io/osm_buildings.h"
#include "uavplan/core/text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "uavplan/core/geometry.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/text_input.h"

namespace uavplan {
namespace {

using nlohmann::json;

constexpr double kFootM = 0.3048;
constexpr double kInchM = 0.0254;

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// A leading non-negative decimal number; the rest of the text is left in s.
std::optional<double> take_number(std::string_view& s) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::fixed);
  if (ec != std::errc() || ptr == s.data() || !std::isfinite(v) || v < 0.0) return std::nullopt;
  s.remove_prefix(static_cast<std::size_t>(ptr - s.data()));
  return v;
}

std::optional<double> non_negative(const json& v) {
  if (v.is_number()) {
    const double x = v.get<double>();
    if (std::isfinite(x) && x >= 0.0) return x;
    return std::nullopt;
  }
  if (v.is_string()) return parse_osm_length_m(v.get<std::string>());
  return std::nullopt;
}

struct OsmReader {
  const std::string& file;
  const GeoFrame& frame;
  const BuildingOptions& opt;
  BuildingCounts& counts;
  std::vector<Prism>& out;

  [[noreturn]] void fail(const std::string& place, const std::string& what) const {
    throw InputError(file, 0, place, what);
  }

  Vec2 position(const json& p, const std::string& place) const {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
      fail(place, "expected a position [lon, lat] or [lon, lat, alt]");
    const double lon = p[0].get<double>(), lat = p[1].get<double>();
    if (!(lon >= -180.0 && lon <= 180.0 && lat >= -90.0 && lat <= 90.0))
      fail(place, "position is not WGS84 longitude, latitude in degrees (RFC 7946 GeoJSON)");
    const Vec3 local = frame.to_local(lat, lon, frame.origin().alt_m);
    return {local.x(), local.y()};
  }

  // The outer ring (first ring) of a polygon's coordinates.
  void polygon(const json& rings, const std::string& place, double z_min, double z_max) const {
    if (!rings.is_array() || rings.empty() || !rings[0].is_array())
      fail(place, "expected a polygon: a list of linear rings");
    const json& ring = rings[0];
    std::vector<Vec2> pts;
    pts.reserve(ring.size());
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 p = position(ring[i], place + "[0][" + std::to_string(i) + "]");
      if (pts.empty() || (p - pts.back()).norm() > 1e-6) pts.push_back(p);
    }
    if (pts.size() >= 2 && (pts.front() - pts.back()).norm() <= 1e-6) pts.pop_back();
    if (pts.size() < 3 || std::abs(polygon_signed_area(pts)) < 1e-9) {
      ++counts.skipped;  // a footprint with no area blocks nothing
      return;
    }
    out.push_back(Prism{std::move(pts), z_min, z_max});
  }

  void feature(const json& f, const std::string& place) const {
    if (!f.is_object()) fail(place, "expected a GeoJSON Feature object");
    const auto g = f.find("geometry");
    if (g == f.end() || g->is_null()) {
      ++counts.skipped;
      return;
    }
    static const json kEmpty = json::object();
    const auto pit = f.find("properties");
    const json& props = (pit != f.end() && pit->is_object()) ? *pit : kEmpty;
    geometry(*g, place + ".geometry", props);
  }

  void geometry(const json& g, const std::string& place, const json& props) const {
    if (!g.is_object() || !g.contains("type") || !g["type"].is_string())
      fail(place, "expected a GeoJSON geometry with a type");
    const std::string type = g["type"].get<std::string>();
    if (type == "GeometryCollection") {
      if (!g.contains("geometries") || !g["geometries"].is_array())
        fail(place, "a GeometryCollection needs 'geometries'");
      for (std::size_t i = 0; i < g["geometries"].size(); ++i)
        geometry(g["geometries"][i], place + ".geometries[" + std::to_string(i) + "]", props);
      return;
    }
    if (type != "Polygon" && type != "MultiPolygon") {
      ++counts.skipped;  // points and lines carry no footprint
      return;
    }
    if (!g.contains("coordinates") || !g["coordinates"].is_array()) fail(place, "missing 'coordinates'");
    double top = 0.0;
    if (const auto h = props.contains("height") ? non_negative(props["height"]) : std::nullopt; h && *h > 0.0) {
      top = *h;
      ++counts.from_height;
    } else if (const auto lv =
                   props.contains("building:levels") ? non_negative(props["building:levels"]) : std::nullopt;
               lv && *lv > 0.0) {
      const auto roof = props.contains("roof:levels") ? non_negative(props["roof:levels"]) : std::nullopt;
      top = (*lv + roof.value_or(0.0)) * opt.level_height_m;
      ++counts.from_levels;
    } else {
      top = opt.default_height_m;
      ++counts.defaulted;
    }
    double bottom = 0.0;
    if (const auto mh = props.contains("min_height") ? non_negative(props["min_height"]) : std::nullopt) {
      bottom = *mh;
    } else if (const auto ml =
                   props.contains("building:min_level") ? non_negative(props["building:min_level"]) : std::nullopt) {
      bottom = *ml * opt.level_height_m;
    }
    if (!(top > bottom)) {  // a part that starts at or above its own top is a tagging error: say so
      const std::string buf = strf(
          "the building's bottom (min_height or building:min_level: %g m) is not below its top (%g m)", bottom, top);
      fail(place, buf);
    }
    const json& c = g["coordinates"];
    const std::string cplace = place + ".coordinates";
    if (type == "Polygon") {
      polygon(c, cplace, opt.base_z_m + bottom, opt.base_z_m + top);
    } else {
      for (std::size_t i = 0; i < c.size(); ++i)
        polygon(c[i], cplace + "[" + std::to_string(i) + "]", opt.base_z_m + bottom, opt.base_z_m + top);
    }
  }
};

}  // namespace

std::optional<double> parse_osm_length_m(std::string_view text) {
  std::string_view s = trim(text);
  const auto v = take_number(s);
  if (!v) return std::nullopt;
  s = trim(s);
  if (s.empty() || s == "m" || s == "meter" || s == "meters" || s == "metre" || s == "metres") return *v;
  if (s == "ft" || s == "feet" || s == "foot") return *v * kFootM;
  if (s.front() == '\'') {  // feet and inches: 12' or 12'6"
    s = trim(s.substr(1));
    if (s.empty()) return *v * kFootM;
    const auto inches = take_number(s);
    if (!inches || trim(s) != "\"") return std::nullopt;
    return *v * kFootM + *inches * kInchM;
  }
  return std::nullopt;
}

std::vector<Prism> buildings_from_geojson(const std::string& text, const std::string& file, const GeoFrame& frame,
                                          const BuildingOptions& options, BuildingCounts* counts) {
  const json doc = parse_json_file(text, file);
  BuildingCounts local_counts;
  std::vector<Prism> out;
  const OsmReader r{file, frame, options, counts ? *counts : local_counts, out};
  if (!doc.is_object() || !doc.contains("type") || !doc["type"].is_string())
    r.fail("", "expected a GeoJSON object with a 'type'");
  if (doc.contains("crs") && doc["crs"].is_object()) {
    // Pre-RFC 7946 files may name a projected CRS; only WGS84 lon/lat is read.
    const std::string name = doc["crs"].value("/properties/name"_json_pointer, std::string());
    if (name.find("CRS84") == std::string::npos && name.find("4326") == std::string::npos)
      r.fail("crs", "coordinates must be WGS84 longitude, latitude (got crs '" + name + "')");
  }
  const std::string type = doc["type"].get<std::string>();
  if (type == "FeatureCollection") {
    if (!doc.contains("features") || !doc["features"].is_array())
      r.fail("features", "a FeatureCollection needs a 'features' list");
    const json& fs = doc["features"];
    for (std::size_t i = 0; i < fs.size(); ++i) r.feature(fs[i], "features[" + std::to_string(i) + "]");
  } else if (type == "Feature") {
    r.feature(doc, "");
  } else {
    r.geometry(doc, "", json::object());
  }
  return out;
}

}  // namespace uavplan
