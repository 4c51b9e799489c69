#include "uavplan/io/airspace.h"

#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "uavplan/core/geometry.h"
#include "uavplan/core/units.h"
#include "uavplan/io/gdal_session.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"
#include "uavplan/io/text_input.h"

namespace uavplan {
namespace {

using nlohmann::json;

// A circle inclusion fence as the polygon inscribed in it: the allowed area only shrinks.
constexpr int kCircleSides = 64;

struct ZoneReader {
  const std::string& file;
  const GeoFrame& frame;
  const Aabb& bounds;
  Airspace& out;
  std::string name = std::filesystem::path(file).filename().string();

  [[noreturn]] void fail(const std::string& place, const std::string& what) const {
    throw InputError(file, 0, place, what);
  }

  Vec2 local(double lat, double lon, const std::string& place) const {
    if (!(std::isfinite(lat) && std::isfinite(lon) && lon >= -180.0 && lon <= 180.0 && lat >= -90.0 && lat <= 90.0))
      fail(place, "position is not WGS84 latitude, longitude in degrees");
    const Vec3 p = frame.to_local(lat, lon, frame.origin().alt_m);
    return {p.x(), p.y()};
  }

  // A ring of points, closing point dropped; refused when it crosses itself or has no area.
  // `latlon` (the corners as read) loses its closing corner with it.
  std::vector<Vec2> ring(std::vector<Vec2> pts, const std::string& place, std::vector<Vec2>& latlon) const {
    if (pts.size() >= 2 && (pts.front() - pts.back()).norm() <= 1e-6) {
      pts.pop_back();
      latlon.pop_back();
    }
    if (pts.size() < 3 || std::abs(polygon_signed_area(pts)) < 1e-9) fail(place, "a zone needs an area (3 corners)");
    if (const auto x = polygon_self_intersection(pts))
      fail(place, "the zone's boundary crosses itself (edges " + std::to_string(x->first) + " and " +
                      std::to_string(x->second) + ")");
    return pts;
  }

  // A zone's floor or ceiling: metres above mean sea level within the contract's 1e9 m.
  double checked_height(double m, const std::string& place) const {
    if (!(std::abs(m) <= kMaxCoordinate_m))
      fail(place, "a height of " + std::to_string(m) + " m: floors and ceilings lie within +-1e9 m");
    return m;
  }

  void exclusion(Obstacle o, FenceZone as_read) {
    as_read.obstacles = {out.zones.size()};
    out.fence.push_back(std::move(as_read));
    out.zones.push_back(std::move(o));
    out.zone_ids.push_back(name + " zone " + std::to_string(out.zone_ids.size()));
  }

  // The inclusion zone: the bounds' box in x, y, and prisms over the rest of it.
  void inclusion(const std::vector<Vec2>& poly, const std::string& place, FenceZone as_read) {
    as_read.inclusion = true;
    if (out.inclusion_box) fail(place, "a second inclusion zone: one fence bounds the world (their union is not read)");
    Vec2 lo = poly[0], hi = poly[0];
    for (const Vec2& p : poly) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    out.inclusion_box = Aabb{Vec3(lo.x(), lo.y(), bounds.min.z()), Vec3(hi.x(), hi.y(), bounds.max.z())};
    bool holes = false;
    for (std::vector<Vec2>& piece : rectangle_minus_polygon(lo, hi, poly, &holes)) {
      as_read.obstacles.push_back(out.zones.size());
      out.zones.push_back(Prism{std::move(piece), bounds.min.z() - 1.0, bounds.max.z() + 1.0});
      out.zone_ids.push_back(name + " outside the fence");
    }
    if (holes) fail(place, "internal: the area outside the fence has a hole");
    out.fence.push_back(std::move(as_read));
  }

  // A polygon zone of GeoJSON or KML: corners [lon, lat], heights AMSL or none.
  void polygon_zone(const std::vector<Vec2>& lonlat, std::optional<double> floor_amsl,
                    std::optional<double> ceiling_amsl, const std::string& at) {
    const double floor = floor_amsl ? *floor_amsl - frame.origin().alt_m : bounds.min.z() - 1.0;
    const double ceiling = ceiling_amsl ? *ceiling_amsl - frame.origin().alt_m : bounds.max.z() + 1.0;
    if (!(ceiling > floor)) fail(at, "ceiling_m must lie above floor_m");
    FenceZone z;
    z.floor_amsl_m = floor_amsl;
    z.ceiling_amsl_m = ceiling_amsl;
    std::vector<Vec2> pts;
    for (std::size_t i = 0; i < lonlat.size(); ++i) {
      pts.push_back(local(lonlat[i].y(), lonlat[i].x(), at + "[" + std::to_string(i) + "]"));
      z.polygon_latlon.emplace_back(lonlat[i].y(), lonlat[i].x());
    }
    std::vector<Vec2> r = ring(std::move(pts), at, z.polygon_latlon);
    exclusion(Prism{std::move(r), floor, ceiling}, std::move(z));
  }

  // GeoJSON: Polygons and MultiPolygons of features, floor_m / ceiling_m from properties.
  void geojson(const json& doc) {
    // Pointers into the document: nothing read is copied (a deep tree copies recursively).
    const auto features = [&]() -> std::vector<std::pair<const json*, std::string>> {
      if (doc.value("type", "") == "FeatureCollection" && doc.contains("features") && doc["features"].is_array()) {
        std::vector<std::pair<const json*, std::string>> fs;
        for (std::size_t i = 0; i < doc["features"].size(); ++i)
          fs.emplace_back(&doc["features"][i], "features[" + std::to_string(i) + "]");
        return fs;
      }
      if (doc.value("type", "") == "Feature") return {{&doc, ""}};
      fail("type", "expected a GeoJSON FeatureCollection or Feature");
    }();
    static const json kNoProperties = json::object();
    for (const auto& feature : features) {
      const json& f = *feature.first;
      const std::string& place = feature.second;  // named: clang 14 captures no structured binding
      if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object()) continue;
      const json& g = f["geometry"];
      const json& props = f.contains("properties") && f["properties"].is_object() ? f["properties"] : kNoProperties;
      const auto height = [&](const char* key) -> std::optional<double> {
        if (!props.contains(key) || props[key].is_null()) return std::nullopt;
        if (!props[key].is_number()) fail(place + ".properties." + key, "expected metres above mean sea level");
        return checked_height(props[key].get<double>(), place + ".properties." + key);
      };
      const std::optional<double> floor = height("floor_m"), ceiling = height("ceiling_m");
      const std::string type = g.value("type", "");
      if (type != "Polygon" && type != "MultiPolygon") continue;  // points and lines close nothing
      const json& c = g["coordinates"];
      const auto polygon = [&](const json& rings, const std::string& at) {
        if (!rings.is_array() || rings.empty() || !rings[0].is_array()) fail(at, "expected a list of linear rings");
        std::vector<Vec2> lonlat;
        for (std::size_t i = 0; i < rings[0].size(); ++i) {
          const json& p = rings[0][i];
          if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
            fail(at, "expected [lon, lat] positions");
          lonlat.emplace_back(p[0].get<double>(), p[1].get<double>());
        }
        polygon_zone(lonlat, floor, ceiling, at + "[0]");
      };
      const std::string at = place + ".geometry.coordinates";
      if (type == "Polygon") {
        polygon(c, at);
      } else {
        for (std::size_t i = 0; i < c.size(); ++i) polygon(c[i], at + "[" + std::to_string(i) + "]");
      }
    }
  }

  // A zone's `inclusion` flag (QGC's default: true).
  bool is_inclusion(const json& z, const std::string& at) const {
    if (!z.contains("inclusion")) return true;
    if (!z["inclusion"].is_boolean()) fail(at + ".inclusion", "expected true or false");
    return z["inclusion"].get<bool>();
  }

  // A QGC plan's geoFence: polygons [[lat, lon], ...] and circles {center: [lat, lon], radius}.
  void qgc_fence(const json& doc) {
    if (!doc.contains("geoFence") || !doc["geoFence"].is_object()) fail("geoFence", "a .plan without a geoFence");
    const json& fence = doc["geoFence"];
    static const json kNone = json::array();
    const auto list = [&](const char* key) -> const json& {
      if (!fence.contains(key) || fence[key].is_null()) return kNone;
      if (!fence[key].is_array()) fail(std::string("geoFence.") + key, "expected a list of zones");
      return fence[key];
    };
    const json& polygons = list("polygons");
    const json& circles = list("circles");
    for (std::size_t k = 0; k < polygons.size(); ++k) {
      const std::string at = "geoFence.polygons[" + std::to_string(k) + "]";
      const json& z = polygons[k];
      if (!z.is_object() || !z.contains("polygon") || !z["polygon"].is_array())
        fail(at, "expected {polygon: [[lat, lon], ...]}");
      std::vector<Vec2> pts;
      FenceZone as_read;
      for (std::size_t i = 0; i < z["polygon"].size(); ++i) {
        const json& p = z["polygon"][i];
        if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
          fail(at, "expected [lat, lon] corners");
        pts.push_back(local(p[0].get<double>(), p[1].get<double>(), at + ".polygon[" + std::to_string(i) + "]"));
        as_read.polygon_latlon.emplace_back(p[0].get<double>(), p[1].get<double>());
      }
      std::vector<Vec2> r = ring(std::move(pts), at, as_read.polygon_latlon);
      if (is_inclusion(z, at))
        inclusion(r, at, std::move(as_read));
      else
        exclusion(Prism{std::move(r), bounds.min.z() - 1.0, bounds.max.z() + 1.0}, std::move(as_read));
    }
    for (std::size_t k = 0; k < circles.size(); ++k) {
      const std::string at = "geoFence.circles[" + std::to_string(k) + "]";
      const json& z = circles[k];
      static const json kNoCircle;
      const json& c = z.is_object() && z.contains("circle") ? z["circle"] : kNoCircle;
      if (!c.is_object() || !c.contains("center") || !c["center"].is_array() || c["center"].size() < 2 ||
          !c["center"][0].is_number() || !c["center"][1].is_number() || !c.contains("radius") ||
          !c["radius"].is_number())
        fail(at, "expected {circle: {center: [lat, lon], radius: metres}}");
      const double radius = c["radius"].get<double>();
      if (!(radius > 0.0 && radius <= kMaxCoordinate_m))
        fail(at + ".circle.radius", "must be a positive number of metres, at most 1e9");
      const Vec2 centre = local(c["center"][0].get<double>(), c["center"][1].get<double>(), at + ".circle.center");
      FenceZone as_read;
      as_read.center_latlon = Vec2(c["center"][0].get<double>(), c["center"][1].get<double>());
      as_read.radius_m = radius;
      if (!is_inclusion(z, at)) {
        exclusion(Cylinder{centre, radius, bounds.min.z() - 1.0, bounds.max.z() + 1.0}, std::move(as_read));
        continue;
      }
      std::vector<Vec2> gon;
      for (int i = 0; i < kCircleSides; ++i) {
        const double a = 2.0 * kPi * i / kCircleSides;
        gon.push_back(centre + radius * Vec2(std::cos(a), std::sin(a)));
      }
      inclusion(gon, at, std::move(as_read));
    }
  }

  // KML through GDAL's vector drivers: the polygons of every Placemark, in layer and file order.
  void kml(const std::string& text) {
    static std::atomic<unsigned> serial{0};
    const std::string mem = "/vsimem/uavplan_airspace_" + std::to_string(serial++) + ".kml";
    VSILFILE* f =
        VSIFileFromMemBuffer(mem.c_str(), reinterpret_cast<GByte*>(const_cast<char*>(text.data())), text.size(), FALSE);
    if (!f) fail("", "cannot hand the KML to GDAL");
    VSIFCloseL(f);
    struct Unlink {
      const std::string& p;
      ~Unlink() { VSIUnlink(p.c_str()); }
    } unlink{mem};
    const QuietGdal quiet;
    GDALDatasetUniquePtr ds = open_gdal(mem, GdalInput::kml_zones);
    if (!ds) {
      std::string said = gdal_said();
      for (std::size_t at; (at = said.find(mem)) != std::string::npos;) said.replace(at, mem.size(), name);
      fail("", "GDAL cannot read it as KML" + said);
    }
    for (int l = 0; l < ds->GetLayerCount(); ++l) {
      OGRLayer* layer = ds->GetLayer(l);
      int n = 0;
      for (const auto& feature : *layer) {
        const char* fname = feature->GetFieldIndex("Name") >= 0 ? feature->GetFieldAsString("Name") : "";
        const std::string place = std::string("layer '") + layer->GetName() + "' placemark " + std::to_string(n++) +
                                  (fname && *fname ? std::string(" '") + fname + "'" : std::string());
        const auto height = [&](const char* key) -> std::optional<double> {
          const int k = feature->GetFieldIndex(key);
          if (k < 0 || !feature->IsFieldSetAndNotNull(k)) return std::nullopt;
          const std::string v = feature->GetFieldAsString(k);
          char* end = nullptr;
          const double x = std::strtod(v.c_str(), &end);
          if (v.empty() || *end != '\0' || !std::isfinite(x))
            fail(place + "." + key, "expected metres above mean sea level");
          return checked_height(x, place + "." + key);
        };
        const std::optional<double> floor = height("floor_m"), ceiling = height("ceiling_m");
        const OGRGeometry* g = feature->GetGeometryRef();
        if (g) kml_geometry(*g, floor, ceiling, place);
      }
    }
  }

  void kml_geometry(const OGRGeometry& g, std::optional<double> floor, std::optional<double> ceiling,
                    const std::string& place) {
    const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
    if (t == wkbPolygon) {
      const OGRLinearRing* outer = g.toPolygon()->getExteriorRing();
      if (!outer) return;
      std::vector<Vec2> lonlat;
      lonlat.reserve(static_cast<std::size_t>(std::max(0, outer->getNumPoints())));
      for (int i = 0; i < outer->getNumPoints(); ++i) lonlat.emplace_back(outer->getX(i), outer->getY(i));
      polygon_zone(lonlat, floor, ceiling, place);
    } else if (t == wkbMultiPolygon || t == wkbGeometryCollection) {
      const OGRGeometryCollection* c = g.toGeometryCollection();
      for (int i = 0; i < c->getNumGeometries(); ++i)
        kml_geometry(*c->getGeometryRef(i), floor, ceiling, place + " part " + std::to_string(i));
    }  // points and lines close nothing
  }
};

}  // namespace

Airspace read_airspace(const std::string& text, const std::string& file, const GeoFrame& frame, const Aabb& bounds) {
  const std::string ext = std::filesystem::path(file).extension().string();
  Airspace out;
  ZoneReader r{file, frame, bounds, out};
  if (ext == ".kmz") throw InputError(file, 0, "", "a KMZ archive: unzip it and name the .kml inside");
  if (ext == ".kml") {
    r.kml(text);
    return out;
  }
  const json doc = parse_json_file(text, file);
  if (!doc.is_object()) throw InputError(file, 0, "", "expected a JSON object");
  if (ext == ".plan")
    r.qgc_fence(doc);
  else
    r.geojson(doc);
  return out;
}

}  // namespace uavplan
