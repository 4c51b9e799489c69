#include "uavplan/evaluation/metrics.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/mission.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/ground_legs.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

double p1_route_cost(std::span<const Vec3> pts, const World& world, double k1) {
  double j = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    j += k1 * world.p1_threat_cost(pts[i - 1], pts[i]) + (1.0 - k1) * (pts[i] - pts[i - 1]).norm();
  return j;
}

P3Score p3_score(std::span<const Vec3> pts, const World& world, const P3Weights& w) {
  P3Score s;
  const std::size_t m = pts.size();
  if (m == 0) return s;
  s.y1 = polyline_length_m(pts);
  for (const Vec3& p : pts)
    for (const Obstacle& o : world.obstacles()) s.y2 += 1.0 / std::max(point_distance(o, p), 1e-3);
  for (std::size_t i = 1; i + 1 < m; ++i) {
    const Vec3 ba = pts[i - 1] - pts[i], bc = pts[i + 1] - pts[i];
    if (ba.norm() <= 0.0 || bc.norm() <= 0.0) continue;
    const double theta = std::acos(std::clamp(ba.dot(bc) / (ba.norm() * bc.norm()), -1.0, 1.0));
    s.y3 += 1.0 / std::max(theta, 1e-6) - 1.0 / kPi;
  }
  const double direct = (pts.back() - pts.front()).norm();
  s.s1 = direct > 0.0 ? s.y1 / direct : 0.0;
  s.s2 = s.y2 / static_cast<double>(m);
  s.s3 = s.y3;
  s.sc = w.k1 * s.s1 + w.k2 * s.s2 + w.k3 * s.s3;
  return s;
}

int count_reversals(const Trajectory& tr, double over_deg, double within_s) {
  const double cos_limit = std::cos(deg_to_rad(over_deg));
  int count = 0;
  std::size_t k = 1;
  while (k < tr.size()) {
    const Vec3 a = tr[k].p - tr[k - 1].p;
    if (a.norm() <= kSamePoint_m) {
      ++k;
      continue;
    }
    std::size_t m = k + 1;
    for (; m < tr.size() && tr[m - 1].t_s - tr[k].t_s <= within_s; ++m) {
      const Vec3 b = tr[m].p - tr[m - 1].p;
      if (b.norm() > kSamePoint_m && a.dot(b) < cos_limit * a.norm() * b.norm()) break;
    }
    if (m < tr.size() && tr[m - 1].t_s - tr[k].t_s <= within_s) {
      ++count;
      k = m;  // from the leg it turned back on (east, west, east: two)
    } else {
      ++k;
    }
  }
  return count;
}

double backing_up_m(const Trajectory& own, std::span<const Trajectory* const> group, double from_s, double to_s) {
  double back = 0.0;
  for (std::size_t k = 1; k < own.size(); ++k) {
    const Vec3 d = own[k].p - own[k - 1].p;
    if (d.norm() <= kSamePoint_m || group.empty() || own[k - 1].t_s < from_s || own[k].t_s > to_s) continue;
    Vec3 mean = Vec3::Zero();
    for (const Trajectory* g : group)
      mean += (position_at(*g, own[k].t_s) - position_at(*g, own[k - 1].t_s)) / static_cast<double>(group.size());
    if (mean.norm() < 0.1 * d.norm()) continue;
    back += std::max(0.0, -d.dot(mean.normalized()));
  }
  return back;
}

ShapeWindow shape_window(const FormationLog& log, double arrival_s) {
  if (log.phases.empty()) return {};
  ShapeWindow w{log.phases.front().end_s, arrival_s};
  for (std::size_t k = 1; k < log.phases.size(); ++k)
    if (log.phases[k].name == "dismiss") w.to_s = std::min(w.to_s, log.phases[k - 1].end_s);
  return w;
}

double time_in_shape_s(const FormationLog& log, const std::string& uav, const ShapeWindow& window) {
  const auto [from, to] = window;
  double held = std::max(0.0, to - from);
  for (const FormationLog::Break& b : log.breaks)
    if (b.uav == uav) held -= std::max(0.0, std::min(b.to_s, to) - std::max(b.from_s, from));
  return std::max(0.0, held);
}

UavMetrics uav_metrics(const Scenario& sc, const UavSpec& spec, const UavPlan& plan) {
  UavMetrics m;
  const auto& tr = plan.trajectory;
  std::vector<Vec3> pts;
  for (const auto& s : tr) pts.push_back(s.p);
  m.length_m = flown_length_m(tr);
  // Flight time counts from the first movement to the last.
  std::size_t first = 0, last = 0;
  for (std::size_t i = 1; i < tr.size(); ++i)
    if ((tr[i].p - tr[i - 1].p).norm() > 0.0) {
      if (first == 0) first = i;
      last = i;
    }
  if (!tr.empty()) m.departure_s = tr[first > 0 ? first - 1 : 0].t_s;
  if (last > 0) m.flight_time_s = tr[last].t_s - tr[first - 1].t_s;
  // Turn, climb, clearance and height as the verifier sees them: on the take-off and landing
  // legs only the distance to obstacles counts (not to the ground the UAV stands on).
  const GroundLegs legs = ground_legs(sc.world, tr);
  std::optional<Vec3> prev;
  if (spec.heading_rad && !legs.takeoff) prev = heading_vector(*spec.heading_rad);
  const double cap = sc.world.bounds().extent().norm() + 1.0;
  const bool has_ground = sc.world.bounds().extent().z() > 0.0;
  m.min_clearance_m = pts.size() == 1 ? sc.world.clearance(pts[0], cap) : World::kInf;
  m.min_agl_m = World::kInf;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Vec3 seg = pts[i] - pts[i - 1];
    if (seg.norm() <= 0.0) continue;
    if (legs.covers(i)) {
      // Only the least clearance counts: each query stops at the least one so far (same result).
      m.min_clearance_m = sc.world.segment_obstacle_clearance(pts[i - 1], pts[i], std::min(cap, m.min_clearance_m));
      continue;
    }
    m.max_climb_deg = std::max(m.max_climb_deg, rad_to_deg(std::abs(pitch_rad(seg))));
    if (prev) m.max_turn_deg = std::max(m.max_turn_deg, rad_to_deg(turn_rad(*prev, seg)));
    prev = seg;
    m.min_clearance_m = sc.world.segment_clearance(pts[i - 1], pts[i], std::min(cap, m.min_clearance_m));
    if (has_ground) m.min_agl_m = std::min(m.min_agl_m, sc.world.lowest_height_above_ground(pts[i - 1], pts[i]));
  }
  m.p1_cost = p1_route_cost(plan.waypoints, sc.world);
  m.p3 = p3_score(plan.waypoints, sc.world);
  // In the air: a fixed wing's taxi to its runway turns as it must on the ground.
  Trajectory air;
  for (const TrajectorySample& s : tr)
    if (!sc.world.on_ground(s.p)) air.push_back(s);
  m.reversals = count_reversals(air);
  return m;
}

namespace {

// A formation's flight quality per UAV and in total: time in shape, breaks, backing up.
void add_formation_metrics(Plan& plan, const std::vector<const UavPlan*>& flown) {
  if (!plan.formation) return;
  std::vector<const Trajectory*> group;
  group.reserve(flown.size());
  for (const UavPlan* up : flown) group.push_back(&up->trajectory);
  double in_shape = 0.0, back = 0.0;
  for (UavPlan& up : plan.uavs) {
    if (up.trajectory.empty() || up.metrics.empty()) continue;
    double breaks = 0.0;
    for (const FormationLog::Break& b : plan.formation->breaks) breaks += b.uav == up.id;
    const ShapeWindow w = shape_window(*plan.formation, up.arrival_s);
    const double held = time_in_shape_s(*plan.formation, up.id, w);
    const double backed = backing_up_m(up.trajectory, group, w.from_s, w.to_s);
    up.metrics["time_in_shape_s"] = held;
    up.metrics["breaks"] = breaks;
    up.metrics["backing_up_m"] = backed;
    // Valid, but not what a formation is flown for: said, not hidden in a total.
    constexpr double kMostOfTheFlight = 0.5;
    if (const double span = w.to_s - w.from_s; span > 0.0 && held < kMostOfTheFlight * span)
      plan.notes.push_back(
          strf("%s kept its slot %.0f s of the %.0f s in formation (%.0f %%, %s): out of shape for "
               "most of the flight",
               up.id.c_str(), held, span, 100.0 * held / span,
               count_text(static_cast<std::size_t>(breaks), "break").c_str()));
    in_shape += held, back += backed;
  }
  plan.metrics["time_in_shape_s"] = in_shape;
  plan.metrics["breaks"] = static_cast<double>(plan.formation->breaks.size());
  plan.metrics["backing_up_m"] = back;
}

// Whether the scenario's mission type declares the metric (MissionDeclaration::metrics).
bool declares_metric(const Scenario& sc, const std::string& metric) {
  const Mission* mission = find_mission(sc.mission.type);
  if (!mission) return false;
  const auto& m = mission->declaration().metrics;
  return std::find(m.begin(), m.end(), metric) != m.end();
}

// The smallest distance between two flown UAVs (for formation_mission, while either is in the
// air). Only pairs whose lower bound is within a reach are measured, nearest bound first, until a
// bound clears the smallest distance found; a reach that held none nearer than itself grows
// fourfold (the pairs it measured are not measured again), up to every pair.
double smallest_separation_m(const Scenario& sc, const std::vector<const UavPlan*>& flown) {
  const Mission* mission = find_mission(sc.mission.type);
  if (flown.size() < 2) return World::kInf;
  std::vector<const Trajectory*> trs;
  trs.reserve(flown.size());
  double widest_m = 0.0;
  for (const UavPlan* up : flown) {
    trs.push_back(&up->trajectory);
    widest_m = std::max(widest_m, sc.find_uav(up->id)->radius_m);
  }
  const SweptBoxes boxes(trs);
  const double extent_m = boxes.extent_m();
  double min_sep = World::kInf, done_m = 0.0;
  // A plan that verified keeps its pairs at least the separation apart: a first reach of twice
  // that mostly holds the nearest pair.
  double reach_m = std::max({2.0 * sc.mission.separation_m, 4.0 * widest_m, extent_m / 1024.0, kTinyDivisor});
  for (;;) {
    std::vector<SweptBoxes::NearPair> pairs = boxes.pairs_within(reach_m);
    std::sort(pairs.begin(), pairs.end(), [](const SweptBoxes::NearPair& a, const SweptBoxes::NearPair& b) {
      return a.bound_m < b.bound_m || (a.bound_m == b.bound_m && (a.i < b.i || (a.i == b.i && a.j < b.j)));
    });
    for (const SweptBoxes::NearPair& pr : pairs) {
      if (pr.bound_m >= min_sep) break;
      if (pr.bound_m < done_m) continue;
      // The mission's own measure where it has one (an airfield's: in the air only).
      const std::optional<double> own = mission
                                            ? mission->pair_distance_m(sc, *sc.find_uav(flown[pr.i]->id), *trs[pr.i],
                                                                       *sc.find_uav(flown[pr.j]->id), *trs[pr.j])
                                            : std::nullopt;
      min_sep = std::min(min_sep, own ? *own : boxes.closest_below(trs, pr.i, pr.j, min_sep).distance_m);
    }
    if (min_sep < reach_m || reach_m > extent_m) return min_sep;
    done_m = reach_m;
    reach_m *= 4.0;
  }
}

}  // namespace

void compute_metrics(const Scenario& sc, Plan& plan) {
  double t_min = World::kInf, t_max = -World::kInf, l_min = World::kInf, l_max = -World::kInf;
  double total = 0.0, p3_total = 0.0;
  std::vector<const UavPlan*> flown;
  const std::vector<Arrival> arrivals = arrival_points(sc);
  for (UavPlan& up : plan.uavs) {
    const UavSpec* spec = sc.find_uav(up.id);
    if (up.trajectory.empty()) up.length_m = 0.0;  // flew nothing
    if (!spec || up.trajectory.empty()) continue;
    const UavMetrics m = uav_metrics(sc, *spec, up);
    up.length_m = m.length_m;
    up.metrics = {{"length_m", m.length_m},
                  {"departure_s", m.departure_s},
                  {"flight_time_s", m.flight_time_s},
                  {"max_turn_deg", m.max_turn_deg},
                  {"max_climb_deg", m.max_climb_deg},
                  {"p1_cost", m.p1_cost},
                  {"p3_score", m.p3.sc},
                  {"p3_y1", m.p3.y1},
                  {"p3_y2", m.p3.y2},
                  {"p3_y3", m.p3.y3},
                  {"reversals", m.reversals}};
    if (std::isfinite(m.min_clearance_m)) {
      up.metrics["min_clearance_m"] = m.min_clearance_m;             // from the UAV's centre
      up.metrics["min_gap_m"] = m.min_clearance_m - spec->radius_m;  // from its body
    }
    if (std::isfinite(m.min_agl_m)) up.metrics["min_agl_m"] = m.min_agl_m;
    total += m.length_m;
    p3_total += m.p3.sc;
    // Arrival (contract): at its goal to stay; a UAV without a goal (it lands) at its last row.
    const std::size_t i = static_cast<std::size_t>(spec - sc.uavs.data());
    up.arrival_s = spec->goal ? arrival_s(*spec, arrivals[i], up.trajectory) : up.trajectory.back().t_s;
    if (std::isfinite(up.arrival_s)) up.metrics["arrival_s"] = up.arrival_s;
    t_min = std::min(t_min, up.arrival_s);
    t_max = std::max(t_max, up.arrival_s);
    l_min = std::min(l_min, m.length_m);
    l_max = std::max(l_max, m.length_m);
    flown.push_back(&up);
  }
  plan.metrics.clear();
  if (flown.empty()) return;
  add_formation_metrics(plan, flown);
  const double min_sep = smallest_separation_m(sc, flown);
  plan.metrics["total_length_m"] = total;
  if (declares_metric(sc, "p3_group_score")) plan.metrics["p3_group_score"] = p3_total;  // P3's score, of a group
  if (std::isfinite(t_max)) plan.metrics["arrival_spread_s"] = t_max - t_min;            // inf: a UAV never arrives
  plan.metrics["length_spread_m"] = l_max - l_min;
  double reversals = 0.0;
  for (const UavPlan* up : flown) reversals += up->metrics.at("reversals");
  plan.metrics["reversals"] = reversals;
  if (std::isfinite(min_sep)) plan.metrics["min_separation_m"] = min_sep;
}

}  // namespace uavplan
