#include "uavplan/io/scenario_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "uavplan/coordination/mission.h"
#include "uavplan/coordination/planning_view.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/io/airspace.h"
#include "uavplan/io/elevation_model.h"
#include "uavplan/io/files.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/osm_buildings.h"
#include "uavplan/io/raster_files.h"
#include "uavplan/io/text_input.h"
#include "uavplan/io/tree_check.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

// The --set overrides applied: the place each one set, and the argument as given.
using Applied = std::vector<std::pair<std::string, std::string>>;

// A YAML node with the key path that leads to it, for error messages.
struct At {
  YAML::Node node;
  std::string path;
  const std::string* file;
  const Applied* applied = nullptr;
  // Where unknown keys are collected, so that one run names every typo; null: the first fails.
  std::vector<std::string>* unknown = nullptr;

  [[noreturn]] void fail(const std::string& what) const { throw error(what); }
  InputError error(const std::string& what) const {
    // A value from the command line is named by its argument, not by a line of the file.
    if (applied)
      for (const auto& [place, arg] : *applied)
        if (path == place || path.rfind(place + ".", 0) == 0 || path.rfind(place + "[", 0) == 0)
          return InputError(*file, 0, arg, what);
    int line = 0;
    if (node.IsDefined()) line = node.Mark().line >= 0 ? node.Mark().line + 1 : 0;
    return InputError(*file, line, path, what);
  }
  bool has(const char* key) const { return node.IsMap() && node[key].IsDefined() && !node[key].IsNull(); }
  At operator[](const char* key) const {
    return {node[key], path.empty() ? std::string(key) : path + "." + key, file, applied, unknown};
  }
  At req(const char* key) const {
    if (!node.IsMap()) fail("expected a mapping");
    if (!has(key)) fail(std::string("missing required key '") + key + "'");
    return (*this)[key];
  }
  At item(std::size_t i) const { return {node[i], path + "[" + std::to_string(i) + "]", file, applied, unknown}; }
  std::size_t size() const { return node.size(); }

  void expect_map() const {
    if (!node.IsMap()) fail("expected a mapping");
  }
  void expect_seq() const {
    if (!node.IsSequence()) fail("expected a list");
  }
  void keys(std::initializer_list<const char*> allowed) const { keys(std::vector<const char*>(allowed)); }
  void keys(const std::vector<const char*>& allowed) const {
    expect_map();
    for (const auto& kv : node) {
      const std::string k = kv.first.Scalar();
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return k == a; })) {
        const std::vector<std::string> names(allowed.begin(), allowed.end());
        const std::string near = nearest_word(k, names);
        std::string why = "unknown key '";
        why += k;
        why += near.empty() ? "' (expected one of: " + word_list(names) + ")" : "' (did you mean '" + near + "'?)";
        const InputError e = At{kv.first, path.empty() ? k : path + "." + k, file, applied}.error(why);
        if (!unknown) throw e;
        unknown->push_back(e.what());
      }
    }
  }

  double number() const {
    if (!node.IsScalar()) fail("expected a number");
    if (node.Tag() == "!") fail("expected a number, got the quoted string \"" + node.Scalar() + "\"");
    if (node.Tag() != "?" && node.Tag() != "tag:yaml.org,2002:int" && node.Tag() != "tag:yaml.org,2002:float")
      fail("expected a number, got a value tagged " + node.Tag());
    const std::string& s = node.Scalar();
    std::string lower = s;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
      fail("must be a finite number, got '" + s + "'");
    double v = 0.0;
    const char* b = s.data();
    if (!s.empty() && s[0] == '+') ++b;
    const auto [ptr, ec] = std::from_chars(b, s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) fail("expected a number, got '" + s + "'");
    if (!std::isfinite(v)) fail("must be a finite number, got '" + s + "'");
    return v;
  }
  double positive() const {
    const double v = coordinate();
    if (!(v > 0.0)) fail("must be positive, got " + node.Scalar());
    return v;
  }
  double non_negative() const {
    const double v = coordinate();
    if (v < 0.0) fail("must not be negative, got " + node.Scalar());
    return v;
  }
  double in_range(double lo, double hi) const {
    const double v = number();
    if (v < lo || v > hi) fail("must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + node.Scalar());
    return v;
  }
  std::int64_t integer() const {
    const double v = number();
    if (v != std::floor(v) || std::abs(v) > 9.0e15) fail("expected an integer, got '" + node.Scalar() + "'");
    return static_cast<std::int64_t>(v);
  }
  std::string text() const {
    if (!node.IsScalar()) fail("expected a string");
    return node.Scalar();
  }
  // A coordinate, velocity or range: within +-kMaxCoordinate_m.
  double coordinate() const {
    const double v = number();
    if (std::abs(v) > kMaxCoordinate_m) fail("must be within +-" + fmt(kMaxCoordinate_m) + ", got " + node.Scalar());
    return v;
  }
  Vec3 vec3() const {
    if (!node.IsSequence() || node.size() != 3) fail("expected a list of 3 numbers [x, y, z]");
    return {item(0).coordinate(), item(1).coordinate(), item(2).coordinate()};
  }
  Vec2 vec2() const {
    if (!node.IsSequence() || node.size() != 2) fail("expected a list of 2 numbers [x, y]");
    return {item(0).coordinate(), item(1).coordinate()};
  }
  static std::string fmt(double x) { return num_text(x); }
};

// The scenario file as a mission type reads its section (Mission::read_section).
class AtSection final : public Section {
 public:
  explicit AtSection(At at) : at_(std::move(at)) {}
  [[noreturn]] void fail(const std::string& what) const override { at_.fail(what); }
  bool has(const char* key) const override { return at_.has(key); }
  std::unique_ptr<Section> at(const char* key) const override { return wrap(at_[key]); }
  std::unique_ptr<Section> req(const char* key) const override { return wrap(at_.req(key)); }
  std::size_t size() const override { return at_.size(); }
  std::unique_ptr<Section> item(std::size_t i) const override { return wrap(at_.item(i)); }
  bool is_map() const override { return at_.node.IsMap(); }
  void expect_seq() const override { at_.expect_seq(); }
  void keys(std::initializer_list<const char*> allowed) const override { at_.keys(allowed); }
  double number() const override { return at_.number(); }
  double positive() const override { return at_.positive(); }
  double non_negative() const override { return at_.non_negative(); }
  std::int64_t integer() const override { return at_.integer(); }
  std::string text() const override { return at_.text(); }
  Vec3 vec3() const override { return at_.vec3(); }

 private:
  static std::unique_ptr<Section> wrap(At at) { return std::make_unique<AtSection>(std::move(at)); }
  At at_;
};

Obstacle read_obstacle(const At& o) {
  o.expect_map();
  const std::string type = o.req("type").text();
  if (type == "sphere") {
    o.keys({"type", "id", "center", "radius"});
    return Sphere{o.req("center").vec3(), o.req("radius").positive()};
  }
  if (type == "cylinder") {
    o.keys({"type", "id", "center", "radius", "z_min", "z_max"});
    Cylinder c{o.req("center").vec2(), o.req("radius").positive(), o.req("z_min").coordinate(),
               o.req("z_max").coordinate()};
    if (!(c.z_min_m < c.z_max_m)) o["z_max"].fail("must be above z_min");
    return c;
  }
  if (type == "box") {
    o.keys({"type", "id", "min", "max"});
    Box b{o.req("min").vec3(), o.req("max").vec3()};
    if ((b.min.array() >= b.max.array()).any()) o["max"].fail("must be above min on every axis");
    return b;
  }
  if (type == "prism") {
    o.keys({"type", "id", "polygon", "z_min", "z_max"});
    const At poly = o.req("polygon");
    poly.expect_seq();
    Prism p;
    for (std::size_t i = 0; i < poly.size(); ++i) p.polygon.push_back(poly.item(i).vec2());
    if (p.polygon.size() >= 2 && p.polygon.front() == p.polygon.back()) p.polygon.pop_back();  // closed ring
    if (p.polygon.size() < 3) poly.fail("a prism needs at least 3 distinct vertices");
    if (polygon_signed_area(p.polygon) == 0.0) poly.fail("polygon has zero area");
    if (const auto x = polygon_self_intersection(p.polygon))
      poly.fail(x->first == x->second
                    ? std::string("self-intersecting polygon: its boundary touches or folds over itself (list "
                                  "the vertices in order around the footprint)")
                    : "self-intersecting polygon: the edge from vertex " + std::to_string(x->first) +
                          " crosses the edge from vertex " + std::to_string(x->second) +
                          " (list the vertices in order around the footprint)");
    p.z_min_m = o.req("z_min").coordinate();
    p.z_max_m = o.req("z_max").coordinate();
    if (!(p.z_min_m < p.z_max_m)) o["z_max"].fail("must be above z_min");
    return p;
  }
  o["type"].fail("unknown obstacle type '" + type + "' (expected sphere, cylinder, box or prism)");
}

TerrainGrid read_terrain(const At& t) {
  t.keys({"type", "origin", "cell", "heights"});
  const std::string type = t.req("type").text();
  if (type != "grid") t["type"].fail("unknown terrain type '" + type + "' (expected grid)");
  const Vec2 origin = t.req("origin").vec2();
  const double cell = t.req("cell").positive();
  const At rows = t.req("heights");
  rows.expect_seq();
  if (rows.size() == 0) rows.fail("needs at least one row");
  const At first = rows.item(0);
  first.expect_seq();
  if (rows.size() * first.size() > kMaxTerrainCells)
    rows.fail(std::to_string(rows.size()) + " x " + std::to_string(first.size()) + " cells, above the " +
              std::to_string(kMaxTerrainCells) + " a terrain may have");
  std::vector<double> h;
  h.reserve(rows.size() * first.size());
  std::size_t nx = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const At row = rows.item(j);
    row.expect_seq();
    if (row.size() == 0) row.fail("empty row");
    if (j == 0) nx = row.size();
    if (row.size() != nx)
      row.fail("has " + std::to_string(row.size()) + " heights, row 0 has " + std::to_string(nx) +
               " (rows must be equal)");
    for (std::size_t i = 0; i < nx; ++i) h.push_back(row.item(i).coordinate());
  }
  return TerrainGrid(origin, cell, static_cast<int>(nx), static_cast<int>(rows.size()), std::move(h));
}

// How far a box lies outside the bounds in x, y (0 when they overlap).
double outside_m(Aabb box, Aabb bounds) {
  box.min.z() = box.max.z() = bounds.min.z() = bounds.max.z() = 0.0;
  return box.distance(bounds);
}

// "N m outside the world's bounds", and where that is far beyond any local map what it likely is.
std::string outside_text(double m) {
  constexpr double kKilometres_m = 10'000.0;
  return (m >= kKilometres_m ? At::fmt(std::round(m / 1000.0)) + " km" : At::fmt(m) + " m") +
         " outside the world's bounds" +
         (m > kFarBeyondAnyMap_m ? " (lat and lon swapped? GeoJSON lists [lon, lat]; origin and a QGC .plan lat, lon)"
                                 : "");
}

// world.buildings: one GeoJSON file (a path, or {file, level_height, default_height}) or a
// list of them; paths are relative to the scenario file. Footprints outside the bounds in x, y
// are dropped (a file none of whose footprints is inside gets a hint).
void read_buildings(const At& b, const std::optional<GeoOrigin>& origin, const Aabb& bounds, std::vector<Obstacle>& out,
                    std::vector<std::string>& hints) {
  if (!origin) b.fail("placing lon/lat footprints needs the scenario's 'origin'");
  const GeoFrame frame(*origin);
  const auto one = [&](const At& e) {
    BuildingOptions opt;
    std::string rel;
    if (e.node.IsScalar()) {
      rel = e.text();
    } else {
      e.keys({"file", "level_height", "default_height"});
      rel = e.req("file").text();
      if (e.has("level_height")) opt.level_height_m = e["level_height"].positive();
      if (e.has("default_height")) opt.default_height_m = e["default_height"].positive();
    }
    const std::filesystem::path path = std::filesystem::path(*e.file).parent_path() / rel;
    std::string text;
    try {
      text = read_text_file(path.string());
    } catch (const InputError&) {
      (e.node.IsScalar() ? e : e["file"]).fail("cannot read the buildings file '" + path.string() + "'");
    }
    std::size_t read = 0, kept = 0;
    double nearest_m = World::kInf;
    for (Prism& p : buildings_from_geojson(text, path.string(), frame, opt)) {
      const Obstacle o = p;
      ++read;
      const double away_m = outside_m(bounding_box(o), bounds);
      nearest_m = std::min(nearest_m, away_m);
      if (away_m > 0.0) continue;
      out.push_back(std::move(p));
      ++kept;
    }
    if (read > 0 && kept == 0)
      hints.push_back((e.node.IsScalar() ? e : e["file"])
                          .error("hint: none of its " + count_text(read, "building") +
                                 " is inside the world; the nearest is " + outside_text(nearest_m))
                          .what());
  };
  if (b.node.IsSequence()) {
    for (std::size_t i = 0; i < b.size(); ++i) one(b.item(i));
  } else {
    one(b);
  }
}

// world.airspace: a list of {file: path} (GeoJSON, a QGC .plan's geoFence), relative to the
// scenario file: exclusion zones become obstacles named after their file; an inclusion fence
// bounds the world in x, y and closes the rest of its box.
void read_airspace_files(const At& a, const std::optional<GeoOrigin>& origin, WorldSpec& ws,
                         std::vector<FenceZone>& fence, std::vector<std::string>& hints) {
  a.expect_seq();
  if (!origin) a.fail("placing lon/lat zones needs the scenario's 'origin'");
  const GeoFrame frame(*origin);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const At e = a.item(i);
    e.keys({"file"});
    const std::filesystem::path path = std::filesystem::path(*e.file).parent_path() / e.req("file").text();
    std::string text;
    try {
      text = read_text_file(path.string());
    } catch (const InputError&) {
      e["file"].fail("cannot read the airspace file '" + path.string() + "'");
    }
    Airspace zones = read_airspace(text, path.string(), frame, ws.bounds);
    ws.obstacle_ids.resize(ws.obstacles.size());
    for (FenceZone& z : zones.fence) {
      for (std::size_t& k : z.obstacles) k += ws.obstacles.size();
      fence.push_back(std::move(z));
    }
    for (std::size_t k = 0; k < zones.zones.size(); ++k) {
      if (const double away_m = outside_m(bounding_box(zones.zones[k]), ws.bounds); away_m > 0.0)
        hints.push_back(e["file"].error("hint: " + zones.zone_ids[k] + " lies " + outside_text(away_m)).what());
      ws.obstacles.push_back(std::move(zones.zones[k]));
      ws.obstacle_ids.push_back(zones.zone_ids[k]);
    }
    if (const auto& box = zones.inclusion_box) {
      // To the micrometre, far below what 1e-7 degrees place (1 cm): a fence through the origin
      // bounds the world at 0, not at the projection's -1.06e-09 or -0.
      const auto micrometres = [](const Vec2& v) -> Vec2 {
        return v.unaryExpr([](double x) { return std::round(x * 1e6) / 1e6 + 0.0; });  // + 0: no -0
      };
      ws.bounds.min.head<2>() = ws.bounds.min.head<2>().cwiseMax(micrometres(box->min.head<2>()));
      ws.bounds.max.head<2>() = ws.bounds.max.head<2>().cwiseMin(micrometres(box->max.head<2>()));
      if ((ws.bounds.max.head<2>().array() <= ws.bounds.min.head<2>().array()).any())
        e["file"].fail("the inclusion fence lies outside the world's bounds");
    }
  }
}

// Rows [t, x, y, z] with strictly increasing times, at least two.
std::vector<TimedPoint> read_timed_path(const At& list) {
  list.expect_seq();
  if (list.size() < 2) list.fail("a trajectory needs at least 2 rows [t, x, y, z], got " + std::to_string(list.size()));
  std::vector<TimedPoint> rows;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const At row = list.item(k);
    if (!row.node.IsSequence() || row.size() != 4) row.fail("expected a row [t, x, y, z]");
    TimedPoint r{row.item(0).coordinate(),
                 Vec3(row.item(1).coordinate(), row.item(2).coordinate(), row.item(3).coordinate())};
    if (!rows.empty() && !(r.t_s > rows.back().t_s))
      row.item(0).fail("times must increase: t = " + At::fmt(r.t_s) + " is not after the previous row's " +
                       At::fmt(rows.back().t_s));
    rows.push_back(r);
  }
  return rows;
}

void check_placed(const At& at, const Vec3& p, const World& world, const std::string& what) {
  check_placed(AtSection(at), p, world, what);
}

// `model: {type: autopilot, tau_v, tau_heading, tau_zdot, tau_z}` (P5 eq. 1; defaults papers.md P5
// section 5) or `{type: point_mass}` (none).
std::optional<AutopilotParams> read_model(const At& m) {
  m.keys({"type", "tau_v", "tau_heading", "tau_zdot", "tau_z"});
  const std::string type = m.req("type").text();
  if (type == "point_mass") {
    for (const char* k : {"tau_v", "tau_heading", "tau_zdot", "tau_z"})
      if (m.has(k)) m[k].fail("a point mass has no time constants");
    return std::nullopt;
  }
  if (type != "autopilot") m["type"].fail("must be 'autopilot' or 'point_mass'");
  AutopilotParams p;
  if (m.has("tau_v")) p.tau_v_s = m["tau_v"].positive();
  if (m.has("tau_heading")) p.tau_heading_s = m["tau_heading"].positive();
  if (m.has("tau_zdot")) p.tau_zdot_s = m["tau_zdot"].positive();
  if (m.has("tau_z")) p.tau_z_s = m["tau_z"].positive();
  return p;
}

UavSpec read_uav(const At& u) {
  u.keys({"id", "start", "heading_deg", "goal", "home", "radius", "speed", "max_turn_deg", "max_climb_deg", "ceiling",
          "sensor_range", "clearance", "min_agl", "max_agl", "max_turn_rate_deg_s", "max_climb_rate", "model"});
  UavSpec s;
  s.id = u.req("id").text();
  if (s.id.empty()) u["id"].fail("must not be empty");
  s.start = u.req("start").vec3();
  if (u.has("goal")) s.goal = u["goal"].vec3();
  if (u.has("home")) s.home = u["home"].vec3();
  if (u.has("heading_deg")) s.heading_rad = deg_to_rad(u["heading_deg"].number());
  if (u.has("radius")) s.radius_m = u["radius"].non_negative();
  if (u.has("clearance")) s.clearance_m = u["clearance"].non_negative();
  if (u.has("min_agl")) {
    s.min_agl_m = u["min_agl"].non_negative();
    s.min_agl_given = true;
  }
  if (u.has("max_agl")) {
    s.max_agl_m = u["max_agl"].positive();
    // Room for the body above min_agl and below max_agl, and to lift off into the band.
    if (*s.max_agl_m < s.min_agl_m + 2 * keep_off_m(s) + 0.1)
      u["max_agl"].fail("must exceed min_agl (" + num_text(s.min_agl_m) +
                        " m) by twice the radius plus clearance and " + "0.1 m (" + num_text(2 * keep_off_m(s) + 0.1) +
                        " m): the band has no room for the UAV");
  }
  if (u.has("speed")) {
    const At sp = u["speed"];
    if (sp.node.IsMap()) {
      sp.keys({"min", "cruise", "max"});
      s.speed.cruise_mps = sp.req("cruise").positive();
      s.speed.min_mps = sp.has("min") ? sp["min"].non_negative() : 0.0;
      s.speed.max_mps = sp.has("max") ? sp["max"].positive() : s.speed.cruise_mps;
      if (s.speed.min_mps > s.speed.cruise_mps) sp["min"].fail("must not exceed cruise");
      if (s.speed.max_mps < s.speed.cruise_mps) sp["max"].fail("must not be below cruise");
    } else {
      s.speed.cruise_mps = s.speed.max_mps = sp.positive();
      s.speed.min_mps = 0.0;
    }
  }
  if (u.has("max_turn_deg")) s.max_turn_rad = deg_to_rad(u["max_turn_deg"].in_range(1e-6, 180.0));
  if (u.has("max_climb_deg")) s.max_climb_rad = deg_to_rad(u["max_climb_deg"].in_range(1e-6, 90.0));
  if (u.has("ceiling")) s.ceiling_m = u["ceiling"].coordinate();
  if (u.has("sensor_range")) s.sensor_range_m = u["sensor_range"].positive();
  if (u.has("max_turn_rate_deg_s")) s.max_turn_rate_rad_s = deg_to_rad(u["max_turn_rate_deg_s"].positive());
  if (u.has("max_climb_rate")) s.max_climb_rate_mps = u["max_climb_rate"].positive();
  if (u.has("model")) s.model = read_model(u["model"]);
  return s;
}

// One document per file: content after a "..." end marker or a second "---" start would be
// dropped by a loader that reads the first document. Markers stand at the start of a line and
// cannot occur inside a scalar, so lines tell. (yaml-cpp 0.7's LoadAll would say it too, but it
// loops forever on input such as a leading ',': jbeder/yaml-cpp#1040, fixed after 0.7.)
void check_single_document(const std::string& text, const std::string& file) {
  bool content = false, ended = false;
  int line = 0;
  for (std::size_t at = 0; at < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view l(text.data() + at, end - at);
    at = end + 1;
    const auto marker = [&](std::string_view m) {
      return l.substr(0, 3) == m && (l.size() == 3 || l[3] == ' ' || l[3] == '\t');
    };
    const std::size_t first = l.find_first_not_of(" \t");
    const bool blank = first == std::string_view::npos || l[first] == '#';
    if (marker("---")) {
      if (content || ended)
        throw InputError(file, line + 1, "", "a second YAML document (after '---'): a scenario file holds one");
      content = l.find_first_not_of(" \t", 3) != std::string_view::npos && l[l.find_first_not_of(" \t", 3)] != '#';
    } else if (marker("...")) {
      ended = true;
    } else if (!blank && !(l[0] == '%' && !content)) {
      if (ended)
        throw InputError(file, line + 1, "",
                         "content after the document's end ('...'): a scenario file holds one document");
      content = true;
    }
  }
}

// What planning would find out too late: UAVs that cannot be where the scenario puts them, a
// mission without the goals it needs, an obstacle that leaves no world.
// An obstacle whose box holds the whole world leaves no room to fly.
void check_room(const At& obstacles, const World& w) {
  for (std::size_t k = 0; k < w.obstacles().size() && k < obstacles.size(); ++k) {
    const Aabb b = bounding_box(w.obstacles()[k]).inflated(1e-9);
    if (std::holds_alternative<Box>(w.obstacles()[k]) && b.contains(w.bounds().min) && b.contains(w.bounds().max))
      obstacles.item(k).fail("covers the whole world: nothing can fly there");
  }
}

// "independent and route": the names of the registered types whose declaration has `has`.
template <class Pred>
std::string missions_that(Pred has) {
  std::vector<std::string> names;
  for (const Mission* m : missions())
    if (has(m->declaration())) names.push_back(m->declaration().name);
  return word_list(names, "and");
}

// A home on the ground, in the world, with room to lift off, for a UAV that starts and ends in
// the air of a mission planned UAV by UAV.
void check_home(const At& ui, const Scenario& sc, const UavSpec& u) {
  const At h = ui["home"];
  const World& w = sc.world;
  if (!find_mission(sc.mission.type)->declaration().flies_homes)
    h.fail("a home is flown by " + missions_that([](const MissionDeclaration& d) { return d.flies_homes; }) +
           " missions (a " + sc.mission.type + " mission's UAVs take off from their starts)");
  if (!w.in_bounds(*u.home)) h.fail("outside the world bounds");
  if (!w.on_ground(*u.home))
    h.fail("must lie on the ground (z = the ground there, " + strf("%.10g", w.ground_z(u.home->x(), u.home->y())) +
           " m)");
  if (w.on_ground(u.start)) ui["start"].fail("is on the ground with a home: a UAV with a home starts in the air");
  if (u.goal && w.on_ground(*u.goal)) ui["goal"].fail("is on the ground with a home: a UAV with a home lands there");
  if (const std::string why = ground_column_problem(sc, u, *u.home); !why.empty()) h.fail("cannot take off: " + why);
}

// A start, goal or home on the ground (within World::on_ground's millimetre) is put exactly on
// it: the verifier measures a body's clearance from the ground exactly, and a height copied
// from a message to a few digits would leave the body micrometres inside it.
void on_the_ground(Scenario& sc) {
  const World& w = sc.world;
  const auto settle = [&](Vec3& p) {
    if (w.on_ground(p)) p.z() = w.ground_z(p.x(), p.y());
  };
  for (UavSpec& u : sc.uavs) {
    settle(u.start);
    if (u.goal) settle(*u.goal);
    if (u.home) settle(*u.home);
  }
}

void check_uavs_fit(const At& uavs, const Scenario& sc) {
  const World& w = sc.world;
  // (a formation's goals are its slots at the end; a formation_mission's UAVs land on the runway)
  const bool goals_needed = find_mission(sc.mission.type)->declaration().needs_goals;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    const At ui = uavs.item(i);
    if (goals_needed && !u.goal)
      ui.fail("missing required key 'goal' (every UAV of a mission of type " + sc.mission.type + " needs one)");
    for (const MovingObstacle& m : w.moving())
      if ((m.position_at(0.0) - u.start).norm() < m.radius_m + u.radius_m)
        ui["start"].fail("inside moving obstacle '" + m.id + "' at t = 0");
    for (std::size_t j = 0; j < i; ++j)
      if ((sc.uavs[j].start - u.start).norm() < sc.uavs[j].radius_m + u.radius_m)
        ui["start"].fail("closer to " + sc.uavs[j].id + "'s start than their radii: two UAVs cannot start there");
    if (u.min_agl_m > 0.0 && w.bounds().extent().z() <= 0.0)
      ui["min_agl"].fail("a flat world (no height) has no room above its ground");
    if (u.max_agl_m && w.bounds().extent().z() <= 0.0)
      ui["max_agl"].fail("a flat world (no height) has no ground to follow");
    if (u.home) check_home(ui, sc, u);
  }
  const std::vector<PlacementProblem> placed = placement_problems(sc);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    if (!placed[i].start.empty()) uavs.item(i)["start"].fail("cannot be planned from: " + placed[i].start);
    if (!placed[i].goal.empty()) uavs.item(i)["goal"].fail("cannot be planned to: " + placed[i].goal);
  }
}

// At least as many as the values written in the text (each value but the last is followed by a
// comma, a colon or a line break), counted without parsing it.
std::size_t written_values_bound(std::string_view text) {
  std::size_t n = 1;
  for (char c : text) n += c == ',' || c == ':' || c == '\n';
  return n;
}

YAML::Node parse_yaml(const std::string& raw, const std::string& file) {
  const std::string text = checked_text(raw, file);
  if (const std::size_t n = written_values_bound(text); n > kMaxWrittenValues)
    throw InputError(file, 0, "",
                     "holds about " + std::to_string(n) + " values; a scenario holds at most " +
                         std::to_string(kMaxWrittenValues) +
                         " (an inline terrain of about 2000 x 2000 cells), so that it loads in bounded memory");
  const bool json = file.size() >= 5 && file.compare(file.size() - 5, 5, ".json") == 0;
  if (json) {
    try {
      const auto parsed = nlohmann::json::parse(text, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
        if (depth > static_cast<int>(kMaxJsonDepth)) throw std::length_error("deep");
        return false;  // keeps nothing: the check is for JSON's syntax
      });
      (void)parsed;
    } catch (const nlohmann::json::exception& e) {
      int line = 0;
      const std::string what = json_error_text(e, text, line);
      throw InputError(file, line, "", "JSON " + what);
    } catch (const std::length_error&) {
      throw InputError(file, 0, "", "arrays and objects nest more than " + std::to_string(kMaxJsonDepth) + " deep");
    }
  }
  check_single_document(text, file);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    // yaml-cpp says "bad file" when its parser's depth guard trips (about 500 nested levels).
    const std::string what =
        e.msg == "bad file" ? "nested too deeply (a scenario needs a few levels, not hundreds)" : e.msg;
    throw InputError(file, e.mark.line >= 0 ? e.mark.line + 1 : 0, "", "YAML syntax error: " + what);
  }
  check_tree(root, file, kMaxScenarioValues);
  return root;
}

// Sets one --set override into the tree; returns the place it set and the argument as given.
std::pair<std::string, std::string> apply_override(YAML::Node& root, const std::string& key, const std::string& value,
                                                   const std::string& file) {
  const std::string place = "--set " + key + "=" + value;
  if (key.empty()) throw InputError(file, 0, place, "empty key");
  const std::string path = key.find_first_of(".[") == std::string::npos ? "planner.params." + key : key;
  YAML::Node v;
  try {
    v = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw InputError(file, 0, place, "value is not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(file, 0, place, "the scenario is not a mapping");
  const KeyPath kp = split_key_path(path);
  if (!kp.error.empty()) throw InputError(file, 0, place, kp.error);
  YAML::Node cur;
  cur.reset(root);
  for (std::size_t s = 0; s < kp.steps.size(); ++s) {
    const KeyPath::Step& step = kp.steps[s];
    const bool last = s + 1 == kp.steps.size();
    YAML::Node next;
    if (step.index) {
      if (!cur.IsSequence() || *step.index >= cur.size())
        throw InputError(file, 0, place, "no list element " + std::to_string(*step.index));
      next.reset(cur[*step.index]);
    } else {
      if (!cur.IsMap() && !cur.IsNull()) throw InputError(file, 0, place, "'" + step.key + "' is not inside a mapping");
      if (!last && !cur[step.key].IsDefined()) cur[step.key] = YAML::Node(YAML::NodeType::Map);  // create the way
      next.reset(cur[step.key]);
    }
    if (last) {
      next = v;  // assigns into the tree (yaml-cpp reference semantics)
      return {path, place};
    }
    cur.reset(next);
  }
  throw InputError(file, 0, place, "empty key");
}

// version, name, seed, origin.
void read_header(const At& top, Scenario& sc) {
  const std::int64_t version = top.req("version").integer();
  if (version != 1)
    top["version"].fail("unsupported version " + std::to_string(version) + " (this build reads version 1)");
  sc.name = top.has("name") ? top["name"].text() : std::string();
  if (top.has("seed")) {
    const std::int64_t seed = top["seed"].integer();
    if (seed < 0) top["seed"].fail("must not be negative");
    sc.seed = static_cast<std::uint64_t>(seed);
  }
  if (top.has("origin")) {
    const At o = top["origin"];
    o.keys({"lat", "lon", "alt"});
    sc.origin = GeoOrigin{o.req("lat").in_range(-90, 90), o.req("lon").in_range(-180, 180),
                          o.has("alt") ? o["alt"].number() : 0.0};
  }
}

Aabb read_bounds(const At& b) {
  b.keys({"min", "max"});
  Aabb bounds{b.req("min").vec3(), b.req("max").vec3()};
  if (!(bounds.min.x() < bounds.max.x()) || !(bounds.min.y() < bounds.max.y()) || !(bounds.min.z() <= bounds.max.z()))
    b["max"].fail("must be above min in x and y, and not below it in z");
  return bounds;
}

void read_threats(const At& list, WorldSpec& ws) {
  list.expect_seq();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const At t = list.item(i);
    t.keys({"type", "id", "position", "weight"});
    const std::string type = t.req("type").text();
    if (type != "radar") t["type"].fail("unknown threat type '" + type + "' (expected radar)");
    ws.radars.push_back(Radar{t.req("position").vec3(), t.has("weight") ? t["weight"].non_negative() : 1.0});
    ws.radar_ids.push_back(t.has("id") ? t["id"].text() : std::string());
  }
}

void read_moving(const At& list, WorldSpec& ws) {
  list.expect_seq();
  std::set<std::string> ids;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const At m = list.item(i);
    m.keys({"id", "radius", "position", "velocity", "trajectory"});
    MovingObstacle mo;
    mo.id = m.has("id") ? m["id"].text() : std::string("m").append(std::to_string(i + 1));
    if (!ids.insert(mo.id).second) m["id"].fail("duplicate moving obstacle id '" + mo.id + "'");
    mo.radius_m = m.req("radius").positive();
    if (m.has("trajectory")) {
      if (m.has("velocity")) m["velocity"].fail("give either 'velocity' or 'trajectory', not both");
      if (m.has("position")) m["position"].fail("a 'trajectory' obstacle starts at its first row; drop 'position'");
      mo.path = read_timed_path(m["trajectory"]);
      mo.position = mo.path.front().p;
    } else {
      if (!m.has("position")) m.fail("needs a 'position' (and a 'velocity') or a 'trajectory' of [t, x, y, z] rows");
      mo.position = m["position"].vec3();
      mo.velocity_mps = m.has("velocity") ? m["velocity"].vec3() : Vec3::Zero();
    }
    ws.moving.push_back(std::move(mo));
  }
}

// world.terrain {file, cell}: an elevation model placed through the origin (io/elevation_model.h).
TerrainGrid read_terrain_file(const At& t, const std::optional<GeoOrigin>& origin, const Aabb& bounds,
                              std::optional<ElevationSource>& source, const StopCondition& stop) {
  t.keys({"file", "cell"});
  if (!origin) t.fail("placing an elevation model needs the scenario's 'origin' (lat, lon, alt)");
  const std::string name = t.req("file").text();
  const std::filesystem::path path = std::filesystem::path(*t.file).parent_path() / name;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    t["file"].fail("cannot read the elevation model '" + path.string() + "'");
  check_elevation_files(path, std::filesystem::path(*t.file).parent_path(), path.string());
  const std::optional<double> cell = t.has("cell") ? std::optional<double>(t["cell"].positive()) : std::nullopt;
  ElevationReadOptions read;
  read.max_cells = kMaxTerrainCells;
  read.stop = stop;
  ElevationModel m = read_elevation_model(path.string(), path.string(), GeoFrame(*origin), bounds, cell, read);
  source = std::move(m.source);
  source->file = name;
  return std::move(m.grid);
}

World read_world(const At& w, Scenario& sc, const StopCondition& stop) {
  const std::optional<GeoOrigin>& origin = sc.origin;
  w.keys({"bounds", "obstacles", "buildings", "airspace", "threats", "terrain", "moving_obstacles"});
  WorldSpec ws;
  ws.bounds = read_bounds(w.req("bounds"));
  if (w.has("obstacles")) {
    const At list = w["obstacles"];
    list.expect_seq();
    for (std::size_t i = 0; i < list.size(); ++i) {
      ws.obstacles.push_back(read_obstacle(list.item(i)));
      ws.obstacle_ids.push_back(list.item(i).has("id") ? list.item(i)["id"].text() : std::string());
    }
  }
  if (w.has("buildings")) read_buildings(w["buildings"], origin, ws.bounds, ws.obstacles, sc.hints);
  if (w.has("airspace")) read_airspace_files(w["airspace"], origin, ws, sc.airspace, sc.hints);
  if (w.has("threats")) read_threats(w["threats"], ws);
  if (w.has("terrain"))
    ws.terrain = w["terrain"].has("file") ? read_terrain_file(w["terrain"], origin, ws.bounds, sc.elevation, stop)
                                          : read_terrain(w["terrain"]);
  if (w.has("moving_obstacles")) read_moving(w["moving_obstacles"], ws);
  try {
    World world(std::move(ws));
    if (w.has("obstacles")) check_room(w["obstacles"], world);
    return world;
  } catch (const std::invalid_argument& e) {
    w.fail(e.what());
  }
}

// Valid values that look like a unit mistake: a turn limit in radians, a speed in km/h (a fast
// UAV over its straight route in seconds), a world measured in kilometres (a few bodies across).
void unit_hints(const At& u, const UavSpec& s, const World& world, std::vector<std::string>& hints) {
  const auto hint = [&](const At& at, const std::string& what) { hints.push_back(at.error("hint: " + what).what()); };
  if (u.has("max_turn_deg") && s.max_turn_rad <= deg_to_rad(kPi))
    hint(u["max_turn_deg"], "a turn limit of " + At::fmt(rad_to_deg(s.max_turn_rad)) +
                                " degrees; if that is radians, write " +
                                At::fmt(rad_to_deg(rad_to_deg(s.max_turn_rad))) + " (the key is in degrees)");
  constexpr double kFast_mps = 20.0, kQuick_s = 30.0;
  const double cruise = s.speed.cruise_mps, route_m = s.goal ? (*s.goal - s.start).norm() : 0.0;
  if (u.has("speed") && cruise >= kFast_mps && route_m > 0.0 && route_m / cruise < kQuick_s)
    hint(u["speed"], "at " + At::fmt(cruise) + " m/s (" + At::fmt(cruise * 3.6) + " km/h) its " + At::fmt(route_m) +
                         " m from start to goal take " + At::fmt(route_m / cruise) +
                         " s; speeds are in m/s (if that is km/h, write " + At::fmt(cruise / 3.6) + ")");
  const Vec3 extent = world.bounds().extent();
  constexpr double kBodies = 20.0;
  if (std::max(extent.x(), extent.y()) < kBodies * s.radius_m)
    hint(u["radius"], "the world is " + At::fmt(std::max(extent.x(), extent.y())) + " m across, " +
                          At::fmt(std::max(extent.x(), extent.y()) / s.radius_m) + " times this UAV's radius of " +
                          At::fmt(s.radius_m) + " m; bounds and radius are in metres");
}

void read_uavs(const At& uavs, Scenario& sc) {
  uavs.expect_seq();
  if (uavs.size() == 0) uavs.fail("needs at least one UAV");
  for (std::size_t i = 0; i < uavs.size(); ++i) {
    const At u = uavs.item(i);
    UavSpec s = read_uav(u);
    if (sc.find_uav(s.id)) u["id"].fail("duplicate UAV id '" + s.id + "'");
    check_placed(u["start"], s.start, sc.world, "start");
    if (s.goal) check_placed(u["goal"], *s.goal, sc.world, "goal");
    unit_hints(u, s, sc.world, sc.hints);
    sc.uavs.push_back(std::move(s));
  }
}

// The common keys, then the type's own section (Mission::read_section).
void read_mission(const At& m, const At& uavs, Scenario& sc) {
  m.expect_map();
  if (m.has("type")) {
    const std::string t = m["type"].text();
    if (!find_mission(t)) m["type"].fail("unknown mission type '" + t + "' (expected " + mission_type_list() + ")");
    sc.mission.type = t;
  }
  // Every type's keys are known: a scenario switches `type` and keeps the others' keys, which
  // the type it names does not read.
  std::vector<std::string> keys;
  for (const MissionKey& k : common_mission_keys()) keys.push_back(k.key);
  for (const Mission* mission : missions())
    for (const MissionKey& k : mission->declaration().keys)
      if (std::find(keys.begin(), keys.end(), k.key) == keys.end()) keys.push_back(k.key);
  std::vector<const char*> allowed;
  allowed.reserve(keys.size());
  for (const std::string& k : keys) allowed.push_back(k.c_str());
  m.keys(allowed);
  const Mission& mission = *find_mission(sc.mission.type);
  if (m.has("separation")) sc.mission.separation_m = m["separation"].non_negative();
  if (m.has("step_s")) sc.mission.step_s = m["step_s"].in_range(kMinStep_s, 3600.0);
  if (m.has("goal_spacing")) sc.mission.goal_spacing_m = m["goal_spacing"].non_negative();
  if (m.has("cruise_agl")) sc.mission.cruise_agl_m = m["cruise_agl"].non_negative();
  mission.read_section(AtSection(m), AtSection(uavs), sc);
}

// Every plan's trajectory has a row at least every second: a flight that would take longer than
// kMaxFlight_s at its cruise speed (its home's legs included), or a fleet whose flights add up to
// more than kMaxFleetFlight_s, is refused here, not after writing millions of rows.
void check_flight_lengths(const At& uavs, const Scenario& sc) {
  double fleet_s = 0.0;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    std::vector<Vec3> route;
    if (u.home) route.push_back(*u.home);
    route.push_back(u.start);
    if (u.goal) {
      route.insert(route.end(), sc.mission.waypoints.begin(), sc.mission.waypoints.end());
      route.push_back(*u.goal);
    }
    if (u.home) route.push_back(*u.home);
    const double length = polyline_length_m(route), flight_s = length / u.speed.cruise_mps;
    fleet_s += flight_s;
    const At ui = uavs.item(i);
    if (flight_s > kMaxFlight_s)
      (ui.has("speed") ? ui["speed"] : ui)
          .fail("at " + At::fmt(u.speed.cruise_mps) + " m/s its " + At::fmt(length) + " m straight route" +
                (u.home ? " (from its home and back)" : "") + " would take " + At::fmt(flight_s) +
                " s; a plan may last at most " + At::fmt(kMaxFlight_s) + " s");
    if (fleet_s > kMaxFleetFlight_s)
      ui.fail("the UAVs' straight routes up to this one add up to " + At::fmt(fleet_s) +
              " s of flight; a plan holds at most " + At::fmt(kMaxFleetFlight_s) +
              " s of flight over all its UAVs (a row a second each)");
  }
}

void read_planner(const At& p, Scenario& sc) {
  p.keys({"algorithm", "params"});
  if (p.has("algorithm")) {
    sc.planner.algorithm = p["algorithm"].text();
    sc.planner.algorithm_given = true;
    try {
      make_planner(sc.planner.algorithm, {});
      mission_algorithm(sc, std::nullopt);
    } catch (const std::invalid_argument& e) {
      p["algorithm"].fail(e.what());
    }
  }
  if (p.has("params")) {
    const At params = p["params"];
    params.expect_map();
    for (const auto& kv : params.node) {
      const At v{kv.second, params.path + "." + kv.first.Scalar(), p.file};
      if (!kv.second.IsScalar()) v.fail("planner parameters must be single values");
      sc.planner.params[kv.first.Scalar()] = kv.second.Scalar();
    }
  }
}

void read_scenario(const At& top, Scenario& sc, const StopCondition& stop) {
  top.keys({"version", "name", "seed", "origin", "world", "uavs", "mission", "planner"});
  read_header(top, sc);
  const At w = top.req("world");
  sc.world = read_world(w, sc, stop);
  const At uavs = top.req("uavs");
  read_uavs(uavs, sc);
  if (top.has("mission")) read_mission(top["mission"], uavs, sc);
  check_flight_lengths(uavs, sc);
  sc.default_min_agl_m = default_min_agl_m(sc);
  on_the_ground(sc);
  check_uavs_fit(uavs, sc);
  if (top.has("planner")) read_planner(top["planner"], sc);
}

}  // namespace

Scenario parse_scenario(const std::string& text, const std::string& file, const Overrides& overrides,
                        const StopCondition& stop) {
  YAML::Node root = parse_yaml(text, file);
  if (!root.IsMap()) throw InputError(file, 0, "", "the top level must be a mapping of scenario keys");
  Applied applied;
  for (const auto& [k, v] : overrides) applied.push_back(apply_override(root, k, v, file));
  std::vector<std::string> unknown;
  const At top{root, "", &file, &applied, &unknown};
  Scenario sc;
  try {
    read_scenario(top, sc, stop);
  } catch (const InputError& e) {
    // The typos met before the error come first: they may be its cause (a required key mistyped).
    unknown.push_back(e.what());
    throw InputError(unknown);
  }
  if (!unknown.empty()) throw InputError(unknown);
  return sc;
}

Scenario load_scenario(const std::string& path, const Overrides& overrides, const StopCondition& stop) {
  return parse_scenario(read_text_file(path), path, overrides, stop);
}

}  // namespace uavplan
