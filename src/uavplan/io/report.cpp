#include "uavplan/io/report.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation_mission/task_points.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/io/palette.h"
#include "uavplan/io/report_assets.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {
namespace {

using ojson = nlohmann::ordered_json;

ojson vec(const Vec3& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson obstacle_json(const Obstacle& o) {
  return std::visit(
      [](const auto& s) -> ojson {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          return {{"shape", "sphere"}, {"center", vec(s.center)}, {"radius", s.radius_m}};
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          return {{"shape", "cylinder"},
                  {"center", {s.center.x(), s.center.y()}},
                  {"radius", s.radius_m},
                  {"z_min", s.z_min_m},
                  {"z_max", s.z_max_m}};
        } else if constexpr (std::is_same_v<T, Box>) {
          return {{"shape", "box"}, {"min", vec(s.min)}, {"max", vec(s.max)}};
        } else {
          ojson poly = ojson::array();
          for (const Vec2& v : s.polygon) poly.push_back({v.x(), v.y()});
          return {{"shape", "prism"}, {"polygon", std::move(poly)}, {"z_min", s.z_min_m}, {"z_max", s.z_max_m}};
        }
      },
      o);
}

ojson terrain_json(const TerrainGrid& t, int max_cells) {
  // Blocks of s x s cells keep the page small; each block shows its highest cell (never hides a peak).
  int s = 1;
  while (static_cast<long long>(t.nx() / s + 1) * (t.ny() / s + 1) > max_cells) ++s;
  const int nx = (t.nx() + s - 1) / s, ny = (t.ny() + s - 1) / s;
  ojson h = ojson::array();
  for (int bj = 0; bj < ny; ++bj)
    for (int bi = 0; bi < nx; ++bi) {
      double m = -World::kInf;
      for (int j = bj * s; j < std::min(t.ny(), (bj + 1) * s); ++j)
        for (int i = bi * s; i < std::min(t.nx(), (bi + 1) * s); ++i) m = std::max(m, t.height(i, j));
      h.push_back(m);
    }
  return {{"origin", {t.origin().x(), t.origin().y()}},
          {"cell", t.cell_m() * s},
          {"nx", nx},
          {"ny", ny},
          {"heights", std::move(h)}};
}

// Speed on the trajectory piece that holds t (0 while holding, before departure and after arrival).
double speed_at(const Trajectory& tr, double t) {
  if (tr.size() < 2 || t < tr.front().t_s || t >= tr.back().t_s) return 0.0;
  const auto it =
      std::upper_bound(tr.begin(), tr.end(), t, [](double v, const TrajectorySample& s) { return v < s.t_s; });
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double dt = b.t_s - a.t_s;
  return dt > 0.0 ? (b.p - a.p).norm() / dt : 0.0;
}

double round6(double v) { return std::round(v * 1e6) / 1e6; }

// Radar shells: the distances at which the threat cost per metre, w / d^4 (P1's J_threat per
// sample point), falls to 1, 0.1 and 0.01 of the fuel cost per metre (J_fuel = L).
ojson radar_json(const Radar& r) {
  ojson shells = ojson::array();
  for (const double level : {1.0, 0.1, 0.01}) shells.push_back(round6(std::pow(r.weight / level, 0.25)));
  return {{"position", vec(r.position)}, {"weight", r.weight}, {"shells_m", std::move(shells)}};
}

// Height profile along the route: distance flown, altitude and the ground under the UAV at
// `samples` evenly spaced distances (and every corner, so steps in the route are not cut).
ojson profile_json(const World& w, const Trajectory& tr, int samples) {
  const double total = flown_length_m(tr);
  ojson s_m = ojson::array(), z_m = ojson::array(), ground_m = ojson::array();
  auto add = [&](double s, const Vec3& p) {
    s_m.push_back(round6(s));
    z_m.push_back(round6(p.z()));
    ground_m.push_back(round6(w.ground_z(p.x(), p.y())));
  };
  const double step = total / std::max(1, samples - 1);
  double s0 = 0.0, next = step;
  add(0.0, tr.front().p);
  for (std::size_t i = 1; i < tr.size(); ++i) {
    const Vec3 a = tr[i - 1].p, b = tr[i].p;
    const double len = (b - a).norm();
    if (len <= 0.0) continue;  // holding
    for (; step > 0.0 && next < s0 + len; next += step) add(next, a + (next - s0) / len * (b - a));
    s0 += len;
    add(s0, b);
  }
  return {{"s_m", std::move(s_m)}, {"z_m", std::move(z_m)}, {"ground_m", std::move(ground_m)}};
}

// Each obstacle's name and what it is: a no-fly zone of an airspace file ("airspace"), the world
// outside an inclusion fence ("fence"), or an obstacle; drawn apart, the zones named.
void mark_airspace(ojson& j, const Scenario& sc) {
  ojson& obstacles = j["obstacles"];
  const auto& ids = sc.world.spec().obstacle_ids;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    obstacles[k]["id"] = k < ids.size() ? ids[k] : std::string();
    obstacles[k]["kind"] = "obstacle";
  }
  for (const FenceZone& z : sc.airspace)
    for (const std::size_t k : z.obstacles)
      if (k < obstacles.size()) obstacles[k]["kind"] = z.inclusion ? "fence" : "airspace";
}

// The world: bounds, obstacles, threats, moving obstacles, terrain.
void add_world(ojson& j, const World& w, const ReportOptions& opt) {
  j["bounds"] = {{"min", vec(w.bounds().min)}, {"max", vec(w.bounds().max)}};
  j["obstacles"] = ojson::array();
  for (const Obstacle& o : w.obstacles()) j["obstacles"].push_back(obstacle_json(o));
  j["threats"] = ojson::array();
  for (const Radar& r : w.radars()) j["threats"].push_back(radar_json(r));
  j["moving"] = ojson::array();
  for (const MovingObstacle& m : w.moving()) {
    ojson jm = {{"id", m.id}, {"radius", m.radius_m}, {"position", vec(m.position)}, {"velocity", vec(m.velocity_mps)}};
    if (!m.path.empty()) {
      jm["trajectory"] = ojson::array();
      for (const TimedPoint& r : m.path) jm["trajectory"].push_back({r.t_s, r.p.x(), r.p.y(), r.p.z()});
    }
    j["moving"].push_back(std::move(jm));
  }
  j["terrain"] = w.terrain() ? terrain_json(*w.terrain(), opt.max_terrain_cells) : ojson(nullptr);
}

// What the mission asks for on the map: a route's via points, P5's task points and airfield.
void add_mission_places(ojson& j, const Scenario& sc) {
  const MissionSpec& m = sc.mission;
  j["via_points"] = ojson::array();
  for (const Vec3& v : m.waypoints) j["via_points"].push_back(vec(v));
  j["task_points"] = ojson::array();
  for (const TaskPoint& tp : phased_section(sc).task_points)
    j["task_points"].push_back(
        {{"position", vec(tp.position)},
         {"radius_m", tp.radius_m},
         {"entry_heading_deg", tp.entry_heading_rad ? ojson(rad_to_deg(*tp.entry_heading_rad)) : ojson(nullptr)}});
  j["airfield"] = m.airfield ? ojson({{"position", vec(m.airfield->position)},
                                      {"runway_heading_deg", rad_to_deg(m.airfield->runway_heading_rad)},
                                      {"runway_length_m", m.airfield->runway_length_m}})
                             : ojson(nullptr);
}

// One UAV with its trajectory, colour by its place in the plan (as in the KML export).
ojson uav_json(const Scenario& sc, const UavPlan& u, std::size_t k, const ReportOptions& opt) {
  const World& w = sc.world;
  const UavSpec* spec = sc.find_uav(u.id);
  ojson traj = ojson::array();
  for (const auto& s : u.trajectory) traj.push_back({s.t_s, s.p.x(), s.p.y(), s.p.z()});
  ojson metrics = ojson::object();
  for (const auto& [key, v] : u.metrics) metrics[key] = round6(v);
  const bool has_height = w.bounds().extent().z() > 0.0;
  return {{"id", u.id},
          {"start", spec ? vec(spec->start) : ojson(nullptr)},
          {"goal", spec && spec->goal ? vec(*spec->goal) : ojson(nullptr)},
          {"status", to_string(u.status)},
          {"message", u.message},
          {"colour", uav_colour(k)},
          {"radius", spec ? spec->radius_m : 0.0},
          {"clearance", spec ? spec->clearance_m : 0.0},
          {"min_agl", spec ? spec->min_agl_m : 0.0},
          {"max_agl", spec && spec->max_agl_m ? ojson(*spec->max_agl_m) : ojson(nullptr)},
          {"length_m", u.length_m},
          {"arrival_s", u.arrival_s},
          {"trajectory", std::move(traj)},
          {"metrics", std::move(metrics)},
          {"profile", has_height && u.trajectory.size() >= 2 ? profile_json(w, u.trajectory, opt.profile_samples)
                                                             : ojson(nullptr)}};
}

// Charts: altitude, speed and distance to the nearest other UAV on a common time grid of the
// flown UAVs.
ojson series_json(const Scenario& sc, const std::vector<const UavPlan*>& flown, double t_end, int samples) {
  const int n = t_end > 0.0 ? std::max(2, samples) : 0;
  ojson times = ojson::array();
  std::vector<std::vector<Vec3>> pos(flown.size());
  for (int i = 0; i < n; ++i) {
    const double t = t_end * i / (n - 1);
    times.push_back(round6(t));
    for (std::size_t k = 0; k < flown.size(); ++k) pos[k].push_back(position_at(flown[k]->trajectory, t));
  }
  // At an airfield (formation_mission) a pair counts only while either UAV is in the air and both
  // are still there (a landed UAV is gone after its last row): the verifier's rule.
  const auto counts = [&](std::size_t k, std::size_t o, int i) {
    if (!sc.mission.airfield) return true;
    const double t = t_end * i / (n - 1), air = sc.mission.airfield->position.z() + kAirborneAbove_m;
    if (t > flown[k]->trajectory.back().t_s || t > flown[o]->trajectory.back().t_s) return false;
    return pos[k][static_cast<std::size_t>(i)].z() > air || pos[o][static_cast<std::size_t>(i)].z() > air;
  };
  ojson series = ojson::array();
  for (std::size_t k = 0; k < flown.size(); ++k) {
    ojson alt = ojson::array(), speed = ojson::array(), nearest = ojson::array();
    for (int i = 0; i < n; ++i) {
      const double t = t_end * i / (n - 1);
      alt.push_back(round6(pos[k][i].z()));
      speed.push_back(round6(speed_at(flown[k]->trajectory, t)));
      double d = World::kInf;
      for (std::size_t o = 0; o < flown.size(); ++o)
        if (o != k && counts(k, o, i)) d = std::min(d, (pos[k][i] - pos[o][i]).norm());
      nearest.push_back(std::isfinite(d) ? ojson(round6(d)) : ojson(nullptr));
    }
    series.push_back({{"id", flown[k]->id},
                      {"altitude_m", std::move(alt)},
                      {"speed_mps", std::move(speed)},
                      {"nearest_m", std::move(nearest)}});
  }
  return {{"t_s", std::move(times)}, {"uavs", std::move(series)}};
}

// A phased mission's phases (P5's form-up ... landing), for bands on the charts.
ojson phases_json(const Plan& plan) {
  ojson phases = ojson::array();
  if (!plan.formation) return phases;
  double from = 0.0;
  for (const FormationLog::Phase& ph : plan.formation->phases) {
    phases.push_back({{"name", ph.name}, {"start_s", round6(from)}, {"end_s", round6(ph.end_s)}});
    from = ph.end_s;
  }
  return phases;
}

}  // namespace

namespace {

// Each flown UAV's track, every k-th row (its last kept) so that at most max_rows remain.
ojson flown_json(const Plan& flown, int max_rows) {
  ojson out = ojson::array();
  for (const UavPlan& u : flown.uavs) {
    const Trajectory& tr = u.trajectory;
    if (tr.size() < 2) continue;
    const auto cap = static_cast<std::size_t>(std::max(max_rows, 2));
    const std::size_t step = (tr.size() + cap - 3) / (cap - 1);  // ceil((n - 1) / (cap - 1)): with the last, cap
    ojson rows = ojson::array();
    const auto row = [&](const TrajectorySample& r) {
      rows.push_back({round6(r.t_s), round6(r.p.x()), round6(r.p.y()), round6(r.p.z())});
    };
    for (std::size_t k = 0; k + 1 < tr.size(); k += step) row(tr[k]);
    row(tr.back());
    out.push_back({{"id", u.id}, {"trajectory", std::move(rows)}});
  }
  return out;
}

}  // namespace

std::string report_data_json(const Scenario& sc, const Plan& plan_in, const std::vector<Violation>& violations,
                             const ReportOptions& opt) {
  // The metrics shown are those of the trajectories shown, whatever the plan file says.
  Plan plan = plan_in;
  compute_metrics(sc, plan);
  ojson j;
  j["name"] = sc.name;
  j["algorithm"] = plan.algorithm;
  j["seed"] = plan.seed;
  j["status"] = to_string(plan.status);
  j["message"] = plan.message;
  j["mission"] = sc.mission.type;
  j["separation_m"] = sc.mission.separation_m;
  add_world(j, sc.world, opt);
  mark_airspace(j, sc);
  add_mission_places(j, sc);
  std::vector<const UavPlan*> flown;
  double t_end = 0.0;
  j["uavs"] = ojson::array();
  for (std::size_t k = 0; k < plan.uavs.size(); ++k) {
    const UavPlan& u = plan.uavs[k];
    j["uavs"].push_back(uav_json(sc, u, k, opt));
    if (u.trajectory.size() >= 2) {
      flown.push_back(&u);
      t_end = std::max(t_end, u.trajectory.back().t_s);
    }
  }
  j["t_end_s"] = t_end;
  j["series"] = series_json(sc, flown, t_end, opt.series_samples);
  j["phases"] = phases_json(plan);
  ojson pm = ojson::object();
  for (const auto& [key, v] : plan.metrics) pm[key] = round6(v);
  j["metrics"] = std::move(pm);
  ojson vs = ojson::array();
  for (const Violation& v : violations) vs.push_back(describe(v));
  j["violations"] = std::move(vs);
  if (opt.flown) j["flown"] = flown_json(*opt.flown, opt.max_flown_rows);
  return j.dump();
}

namespace {

// Inline text must not close its <script> / <style> element early.
std::string escape_for_element(std::string s, std::string_view closing) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '<' && i + 1 < s.size() && s[i + 1] == '/' && s.compare(i + 2, closing.size(), closing) == 0) {
      out += "<\\/";
      ++i;
      continue;
    }
    out += s[i];
  }
  return out;
}

// JSON inside <script>: every '<' written as \u003c (the same JSON string), so no name can close
// the element ("</script") or put the HTML parser into its escaped states ("<!--<script").
std::string json_for_script(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (char c : json) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

std::string html_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string report_html(const Scenario& sc, const Plan& plan, const std::vector<Violation>& violations,
                        const ReportOptions& opt) {
  const std::string data = json_for_script(report_data_json(sc, plan, violations, opt));
  std::string html;
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += "<link rel=\"icon\" href=\"data:,\">\n";
  html += "<title>uavplan report: " + html_escape(sc.name) + "</title>\n";
  html += "<style>\n" + escape_for_element(std::string(report_css()), "style") + "\n</style>\n</head>\n<body>\n";
  html += "<noscript>This report needs JavaScript for its 3-D view and charts.</noscript>\n";
  html += "<div id=\"app\"></div>\n";
  html += "<script type=\"application/json\" id=\"uavplan-data\">" + data + "</script>\n";
  html += "<script>\n" + escape_for_element(std::string(report_js()), "script") + "\n</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace uavplan
