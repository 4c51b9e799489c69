#include "uavplan/io/plan_io.h"

#include <yaml-cpp/yaml.h>
#include <algorithm>
#include <cmath>

#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "uavplan/core/text.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/text_input.h"
#include "uavplan/io/tree_check.h"

namespace uavplan {
namespace {

using Json = nlohmann::ordered_json;  // written: members in the order they are set
// Read: an object is a std::map, so inserting a member never moves the others (an ordered_json
// copies every member so far each time its vector grows: a plan's UAV array, a UAV's rows).
using JsonIn = nlohmann::json;

double r6(double x) {
  const double r = std::round(x * 1e6) / 1e6;
  return r == 0.0 ? 0.0 : r;  // no "-0.0"
}

Json metrics_json(const std::map<std::string, double>& m) {
  Json j = Json::object();
  for (const auto& [k, v] : m) j[k] = std::isfinite(v) ? Json(r6(v)) : Json(nullptr);
  return j;
}

void write_number(double x, std::string& out) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buf[64];
  out.append(buf, nlohmann::detail::to_chars(buf, buf + sizeof buf, x));
}

// A primitive as nlohmann::json::dump writes it; floating-point numbers without a temporary
// string (nlohmann's own shortest round-trip formatting, so the bytes are dump()'s).
void write_primitive(const Json& j, std::string& out) {
  if (!j.is_number_float()) {
    out += j.dump();
    return;
  }
  write_number(j.get<double>(), out);
}

// A UAV's waypoints and trajectory rows are not built as a tree (a third of the time of writing
// a plan went to that): the tree holds binary values in their place, subtype 2 k for UAV k's
// waypoints and 2 k + 1 for its rows, and these are written as write_json would have.
using Splice = std::function<void(std::uint64_t index, std::size_t depth, std::string& out)>;

// Pretty JSON with every all-number array (a waypoint, a trajectory row) on one line.
void write_json(const Json& j, int depth, std::string& out, const Splice& splice) {
  const auto pad = static_cast<std::size_t>(depth) + 1;
  if (j.is_array()) {
    const bool flat = std::all_of(j.begin(), j.end(), [](const Json& e) { return e.is_primitive(); });
    if (flat || j.empty()) {
      out += '[';
      for (std::size_t i = 0; i < j.size(); ++i) {
        if (i) out += ',';
        write_primitive(j[i], out);
      }
      out += ']';
      return;
    }
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out.append(pad, ' ');
      write_json(j[i], depth + 1, out, splice);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out.append(pad - 1, ' ');
    out += ']';
  } else if (j.is_object() && !j.empty()) {
    out += "{\n";
    std::size_t i = 0;
    for (const auto& [k, v] : j.items()) {
      out.append(pad, ' ');
      out += Json(k).dump();
      out += ": ";
      write_json(v, depth + 1, out, splice);
      out += ++i < j.size() ? ",\n" : "\n";
    }
    out.append(pad - 1, ' ');
    out += '}';
  } else if (j.is_binary()) {
    splice(j.get_binary().subtype(), static_cast<std::size_t>(depth), out);
  } else {
    write_primitive(j, out);
  }
}

// An array of `rows` arrays of `Width` numbers (value(i, k)), as write_json writes it.
template <int Width, class Value>
void write_number_rows(std::size_t rows, std::size_t depth, std::string& out, const Value& value) {
  if (rows == 0) {
    out += "[]";
    return;
  }
  out += "[\n";
  for (std::size_t i = 0; i < rows; ++i) {
    out.append(depth + 1, ' ');
    out += '[';
    for (int k = 0; k < Width; ++k) {
      if (k) out += ',';
      write_number(value(i, k), out);
    }
    out += i + 1 < rows ? "],\n" : "]\n";
  }
  out.append(depth, ' ');
  out += ']';
}

void write_points(const std::vector<Vec3>& pts, std::size_t depth, std::string& out) {
  write_number_rows<3>(pts.size(), depth, out, [&](std::size_t i, int k) { return pts[i][k]; });
}

// A row: time, then position.
void write_rows(const Trajectory& tr, std::size_t depth, std::string& out) {
  write_number_rows<4>(tr.size(), depth, out,
                       [&](std::size_t i, int k) { return k == 0 ? tr[i].t_s : tr[i].p[k - 1]; });
}

struct PlanReader {
  const std::string& file;
  const std::string& source;
  // The line of the place is looked up only for the error (a YAML reading of the JSON text).
  [[noreturn]] void fail(const std::string& place, const std::string& what) const {
    int line = 0;
    try {
      line = place.empty() ? 0 : line_of(YAML::Load(source), place);
    } catch (const YAML::Exception&) {
    }
    throw InputError(file, line, place, what);
  }
  const JsonIn& req(const JsonIn& obj, const char* key, const std::string& place) const {
    if (!obj.is_object()) fail(place, "expected an object");
    const auto it = obj.find(key);
    if (it == obj.end()) fail(place, std::string("missing required key '") + key + "'");
    return *it;
  }
  double number(const JsonIn& v, const std::string& place) const {
    if (!v.is_number()) fail(place, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(place, "must be finite");
    return x;
  }
  std::string text(const JsonIn& v, const std::string& place) const {
    if (!v.is_string()) fail(place, "expected a string");
    return v.get<std::string>();
  }
  // Metrics as written: numbers, or null for a value that is not finite (+inf clearance).
  std::map<std::string, double> metrics(const JsonIn& v, const std::string& place) const {
    if (!v.is_object()) fail(place, "expected an object");
    std::map<std::string, double> out;
    for (const auto& [k, x] : v.items()) {
      if (x.is_null())
        out[k] = std::numeric_limits<double>::infinity();
      else
        out[k] = number(x, std::string(place).append(".").append(k));
    }
    return out;
  }
};

// An object whose members are all inserted before it grows: ordered_json keeps members in a
// vector of pairs with a const key, which cannot move, so each growth would deep-copy every
// member so far (a plan's whole UAV array, a UAV's waypoints).
Json object_for(std::size_t members) {
  Json j = Json::object();
  j.get_ref<Json::object_t&>().reserve(members);
  return j;
}

}  // namespace

std::string plan_to_json(const Plan& plan, const PlanWriteOptions& options) {
  Json j = object_for(12);
  j["format"] = "uavplan-plan";
  j["version"] = 1;
  j["scenario"] = plan.scenario;
  j["algorithm"] = plan.algorithm;
  j["seed"] = plan.seed;
  j["status"] = std::string(to_string(plan.status));
  j["message"] = plan.message;
  Json uavs = Json::array();
  uavs.get_ref<Json::array_t&>().reserve(plan.uavs.size());
  for (const UavPlan& u : plan.uavs) {
    Json ju = object_for(12);
    ju["id"] = u.id;
    ju["status"] = std::string(to_string(u.status));
    if (u.reason != Reason::none) ju["reason"] = std::string(to_string(u.reason));
    ju["message"] = u.message;
    // The waypoints and the rows are spliced in as they are written (write_points, write_rows).
    ju["waypoints"] = Json::binary({}, 2 * uavs.size());
    ju["trajectory"] = Json::binary({}, 2 * uavs.size() + 1);
    ju["length_m"] = u.length_m;
    ju["route_length_m"] = u.route_length_m;
    if (std::isfinite(u.arrival_s)) ju["arrival_s"] = u.arrival_s;  // none: never at its goal to stay
    ju["metrics"] = metrics_json(u.metrics);
    ju["stats"] = {{"nodes_expanded", u.stats.nodes_expanded},
                   {"open_max", u.stats.open_max},
                   {"grid_cells", u.stats.grid_cells},
                   {"cell_m", r6(u.stats.cell_m)}};
    uavs.push_back(std::move(ju));
  }
  j["uavs"] = std::move(uavs);
  if (plan.formation) {
    Json phases = Json::array(), breaks = Json::array();
    for (const auto& ph : plan.formation->phases) phases.push_back({{"name", ph.name}, {"end_s", r6(ph.end_s)}});
    for (const auto& b : plan.formation->breaks)
      breaks.push_back({{"uav", b.uav}, {"from_s", r6(b.from_s)}, {"to_s", r6(b.to_s)}});
    j["formation"] = {
        {"eta_s", r6(plan.formation->eta_s)}, {"phases", std::move(phases)}, {"breaks", std::move(breaks)}};
    if (plan.formation->worst_slot_error_m)
      j["formation"]["worst_slot_error_m"] = r6(*plan.formation->worst_slot_error_m);
    if (plan.formation->arrival_spread_s) j["formation"]["arrival_spread_s"] = r6(*plan.formation->arrival_spread_s);
  }
  j["metrics"] = metrics_json(plan.metrics);
  j["timing"] = Json::object();
  if (options.include_timing) {
    j["timing"]["plan_ms"] = std::round(plan.plan_ms * 1000.0) / 1000.0;
    // Per UAV where it was planned on its own (a group or formation is planned as one: no 0.0 rows).
    for (const UavPlan& u : plan.uavs)
      if (u.stats.plan_ms > 0.0) j["timing"][u.id + ".plan_ms"] = std::round(u.stats.plan_ms * 1000.0) / 1000.0;
  }
  std::size_t rows = 0;
  for (const UavPlan& u : plan.uavs) rows += u.trajectory.size() + u.waypoints.size();
  std::string out;
  out.reserve(2048 + 96 * rows);  // a row is about 80 characters
  write_json(j, 0, out, [&](std::uint64_t k, std::size_t depth, std::string& o) {
    const UavPlan& u = plan.uavs[k / 2];
    if (k % 2 == 0)
      write_points(u.waypoints, depth, o);
    else
      write_rows(u.trajectory, depth, o);
  });
  out += '\n';
  return out;
}

namespace {

// nlohmann's tree builder, noting a key met twice in one object (the builder keeps the last).
// sax_parse calls these members statically: no callback per value, as parse(text, callback)
// would make.
class DuplicateKeySax : public DepthLimitedSax {
 public:
  using Base = DepthLimitedSax;
  explicit DuplicateKeySax(JsonIn& tree) : Base(tree) {}
  bool start_object(std::size_t n) {
    keys_.emplace_back();
    return Base::start_object(n);
  }
  bool end_object() {
    keys_.pop_back();
    return Base::end_object();
  }
  bool key(std::string& k) {
    auto& seen = keys_.back();  // few keys an object: a list
    duplicate_ = duplicate_ || std::find(seen.begin(), seen.end(), k) != seen.end();
    seen.push_back(k);
    return Base::key(k);
  }
  bool duplicate() const { return duplicate_; }

 private:
  std::vector<std::vector<std::string>> keys_;  // of the objects open while parsing
  bool duplicate_ = false;
};

// The JSON tree of a plan file: valid JSON, no key twice in one object.
JsonIn parse_plan_json(const std::string& text, const std::string& file) {
  JsonIn j;
  bool duplicate = false, too_deep = false;
  try {
    DuplicateKeySax sax(j);
    JsonIn::sax_parse(text, &sax);
    duplicate = sax.duplicate();
    too_deep = sax.too_deep();
  } catch (const JsonIn::exception& e) {
    throw_json_error(e, text, file);
  }
  if (too_deep)
    throw InputError(file, 0, "",
                     "arrays and objects nest more than " + std::to_string(kMaxJsonDepth) + " deep; not read");
  if (duplicate) {  // nlohmann kept the last of them: name it with its line
    try {
      check_tree(YAML::Load(text), file, static_cast<std::size_t>(-1));
    } catch (const YAML::Exception&) {
    }
    throw InputError(file, 0, "", "a key appears twice in one object");
  }
  return j;
}

// An array of `n` finite numbers, read into `out` (no place names built unless it fails).
bool read_numbers(const JsonIn& v, std::size_t n, double* out) {
  if (!v.is_array() || v.size() != n) return false;
  for (std::size_t k = 0; k < n; ++k) {
    if (!v[k].is_number()) return false;
    out[k] = v[k].get<double>();
    if (!std::isfinite(out[k])) return false;
  }
  return true;
}

// `[t, x, y, z]` rows. The input limits of scenarios hold here too: times from 0 (a mission
// starts at 0; a UAV is at its first row before it) to 1e9 s, coordinates within 1e9 m.
Trajectory read_rows(const PlanReader& r, const JsonIn& tr, const std::string& at) {
  if (!tr.is_array()) r.fail(at + ".trajectory", "expected an array");
  Trajectory rows;
  rows.reserve(tr.size());
  for (std::size_t k = 0; k < tr.size(); ++k) {
    double v[4];
    const bool ok = read_numbers(tr[k], 4, v);
    if (ok && v[0] >= 0.0 && v[0] <= 1e9 && std::max({std::abs(v[1]), std::abs(v[2]), std::abs(v[3])}) <= 1e9) {
      rows.push_back({v[0], Vec3(v[1], v[2], v[3])});
      continue;
    }
    const std::string row = at + ".trajectory[" + std::to_string(k) + "]";
    if (!tr[k].is_array() || tr[k].size() != 4) r.fail(row, "expected [t, x, y, z]");
    const double t_s = r.number(tr[k][0], row);
    if (t_s < 0.0 || t_s > 1e9) r.fail(row, "time must be from 0 to 1e9 s, got " + num_text(t_s));
    for (int a = 1; a <= 3; ++a) r.number(tr[k][a], row);
    r.fail(row, "coordinates must be within 1e9 m");
  }
  return rows;
}

std::vector<Vec3> read_waypoints(const PlanReader& r, const JsonIn& w, const std::string& at) {
  if (!w.is_array()) r.fail(at + ".waypoints", "expected an array");
  std::vector<Vec3> out;
  out.reserve(w.size());
  for (std::size_t k = 0; k < w.size(); ++k) {
    double v[3];
    if (read_numbers(w[k], 3, v)) {
      out.emplace_back(v[0], v[1], v[2]);
      continue;
    }
    const std::string wp = at + ".waypoints[" + std::to_string(k) + "]";
    if (!w[k].is_array() || w[k].size() != 3) r.fail(wp, "expected [x, y, z]");
    for (int a = 0; a < 3; ++a) r.number(w[k][a], wp);
  }
  return out;
}

PlanStats read_stats(const PlanReader& r, const JsonIn& st, const std::string& at) {
  if (!st.is_object()) r.fail(at + ".stats", "expected an object");
  const auto count = [&](const char* key) -> std::uint64_t {
    if (!st.contains(key)) return 0;
    const double v = r.number(st[key], at + ".stats." + key);
    if (v < 0 || v > 1.8e19) r.fail(at + ".stats." + key, "expected a count");
    return static_cast<std::uint64_t>(v);
  };
  PlanStats stats;
  stats.nodes_expanded = count("nodes_expanded");
  stats.open_max = count("open_max");
  stats.grid_cells = count("grid_cells");
  if (st.contains("cell_m")) stats.cell_m = r.number(st["cell_m"], at + ".stats.cell_m");
  return stats;
}

UavPlan read_uav_plan(const PlanReader& r, const JsonIn& ju, const std::string& at) {
  UavPlan u;
  u.id = r.text(r.req(ju, "id", at), at + ".id");
  const auto us = status_from_string(r.text(r.req(ju, "status", at), at + ".status"));
  if (!us) r.fail(at + ".status", "expected solved, partial or failed");
  u.status = *us;
  if (ju.contains("message")) u.message = r.text(ju["message"], at + ".message");
  if (ju.contains("reason")) {
    const auto reason = reason_from_string(r.text(ju["reason"], at + ".reason"));
    if (!reason) r.fail(at + ".reason", "expected none, stopped, budget, no_route, invalid, conflict or rejected");
    u.reason = *reason;
  }
  if (ju.contains("waypoints")) u.waypoints = read_waypoints(r, ju["waypoints"], at);
  u.trajectory = read_rows(r, r.req(ju, "trajectory", at), at);
  if (ju.contains("length_m")) u.length_m = r.number(ju["length_m"], at + ".length_m");
  if (ju.contains("route_length_m")) u.route_length_m = r.number(ju["route_length_m"], at + ".route_length_m");
  if (ju.contains("arrival_s")) u.arrival_s = r.number(ju["arrival_s"], at + ".arrival_s");
  if (ju.contains("metrics")) u.metrics = r.metrics(ju["metrics"], at + ".metrics");
  if (ju.contains("stats")) u.stats = read_stats(r, ju["stats"], at);
  return u;
}

FormationLog read_formation_log(const PlanReader& r, const JsonIn& f) {
  FormationLog log;
  log.eta_s = r.number(r.req(f, "eta_s", "formation"), "formation.eta_s");
  if (f.contains("worst_slot_error_m"))
    log.worst_slot_error_m = r.number(f["worst_slot_error_m"], "formation.worst_slot_error_m");
  if (f.contains("arrival_spread_s"))
    log.arrival_spread_s = r.number(f["arrival_spread_s"], "formation.arrival_spread_s");
  for (const char* key : {"phases", "breaks"}) {
    if (!f.contains(key)) continue;
    const std::string at = std::string("formation.") + key;
    if (!f[key].is_array()) r.fail(at, "expected an array");
    for (std::size_t k = 0; k < f[key].size(); ++k) {
      const JsonIn& e = f[key][k];
      const std::string place = at + "[" + std::to_string(k) + "]";
      if (std::string(key) == "phases")
        log.phases.push_back(
            {r.text(r.req(e, "name", place), place + ".name"), r.number(r.req(e, "end_s", place), place + ".end_s")});
      else
        log.breaks.push_back({r.text(r.req(e, "uav", place), place + ".uav"),
                              r.number(r.req(e, "from_s", place), place + ".from_s"),
                              r.number(r.req(e, "to_s", place), place + ".to_s")});
    }
  }
  return log;
}

}  // namespace

Plan parse_plan(const std::string& raw, const std::string& file) {
  const std::string text = checked_text(raw, file);
  const JsonIn j = parse_plan_json(text, file);
  const PlanReader r{file, text};
  if (!j.is_object()) r.fail("", "the top level must be a JSON object");
  if (r.text(r.req(j, "format", ""), "format") != "uavplan-plan") r.fail("format", "expected \"uavplan-plan\"");
  const JsonIn& ver = r.req(j, "version", "");
  if (!ver.is_number_integer() || ver.get<long long>() != 1)
    r.fail("version", "unsupported version (this build reads version 1)");
  Plan p;
  if (j.contains("scenario")) p.scenario = r.text(j["scenario"], "scenario");
  if (j.contains("algorithm")) p.algorithm = r.text(j["algorithm"], "algorithm");
  if (j.contains("seed")) {
    if (!j["seed"].is_number_unsigned()) r.fail("seed", "expected a non-negative integer");
    p.seed = j["seed"].get<std::uint64_t>();
  }
  if (j.contains("message")) p.message = r.text(j["message"], "message");
  const auto status = status_from_string(r.text(r.req(j, "status", ""), "status"));
  if (!status) r.fail("status", "expected solved, partial or failed");
  p.status = *status;
  const JsonIn& uavs = r.req(j, "uavs", "");
  if (!uavs.is_array()) r.fail("uavs", "expected an array");
  for (std::size_t i = 0; i < uavs.size(); ++i) {
    const std::string at = "uavs[" + std::to_string(i) + "]";
    UavPlan u = read_uav_plan(r, uavs[i], at);
    if (p.find_uav(u.id)) r.fail(at + ".id", "duplicate UAV id '" + u.id + "'");
    p.uavs.push_back(std::move(u));
  }
  if (j.contains("metrics")) p.metrics = r.metrics(j["metrics"], "metrics");
  if (j.contains("formation")) p.formation = read_formation_log(r, j["formation"]);
  // The plan's reason is its first unsolved UAV's; a plan failed with every UAV solved was
  // failed by a rule of the whole mission (finalize_plan).
  if (p.status != Status::solved) {
    p.reason = Reason::rejected;
    for (const UavPlan& u : p.uavs)
      if (!u.solved()) {
        p.reason = u.reason;
        break;
      }
  }
  return p;
}

Plan load_plan(const std::string& path) { return parse_plan(read_text_file(path), path); }

}  // namespace uavplan
