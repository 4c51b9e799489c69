#include "uavplan/coordination/routes/rolling_window.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "uavplan/core/rng.h"

namespace uavplan {

std::vector<ThreatDisc> threat_discs(const UavSpec& u, const std::vector<Track>& tracks, double t_s, double step_s,
                                     double separation_m, std::span<const char> bodies_only) {
  std::vector<ThreatDisc> out;
  out.reserve(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& k = tracks[i];
    const double body = k.is_uav ? std::max(separation_m, k.radius_m + u.radius_m) : k.radius_m + u.radius_m;
    const bool gives_way = i < bodies_only.size() && bodies_only[i];
    if (gives_way || k.commanded) {
      const double r = body + kPlanningMargin_m + (k.commanded ? k.commanded_slack_m : 0.0);
      out.push_back({{k.position(), k.velocity_mps.value_or(Vec3::Zero()), r, t_s}, r, gives_way});
      continue;
    }
    // Seen once: no V_b yet; taken to come straight at the UAV, at least as fast as the UAV can fly.
    const double speed = k.velocity_mps ? k.velocity_mps->norm() : std::max(u.speed.max_mps, k.entered_speed_mps);
    const Vec3 velocity = k.velocity_mps              ? *k.velocity_mps
                          : k.relative_m.norm() > 0.0 ? Vec3(-speed * k.relative_m.normalized())
                                                      : Vec3::Zero();
    out.push_back({{k.position(), velocity, body + step_s * speed + kPlanningMargin_m, t_s}, body + kPlanningMargin_m});
  }
  return out;
}

namespace {

// The route ahead as a polyline from the UAV, with the length flown before each point.
struct Ahead {
  std::vector<Vec3> pts;
  std::vector<double> along;
  Vec3 at(double s, std::size_t* segment_end = nullptr) const {
    for (std::size_t i = 1; i < pts.size(); ++i)
      if (along[i] >= s || i + 1 == pts.size()) {
        if (segment_end) *segment_end = i;
        const double len = along[i] - along[i - 1];
        const double f = len > 0.0 ? std::clamp((s - along[i - 1]) / len, 0.0, 1.0) : 1.0;
        return pts[i - 1] + f * (pts[i] - pts[i - 1]);
      }
    if (segment_end) *segment_end = pts.size();
    return pts.back();
  }
};

// How far along the route ahead its next via point lies (+inf: none ahead).
double next_via_along(const Ahead& a, const std::vector<Vec3>& via) {
  for (std::size_t k = 1; k < a.pts.size(); ++k)
    for (const Vec3& p : via)
      if ((a.pts[k] - p).norm() <= 1e-6) return a.along[k];
  return std::numeric_limits<double>::infinity();
}

Ahead ahead_of(const FlightState& s) {
  Ahead a;
  a.pts.push_back(s.position);
  a.along.push_back(0.0);
  for (const Vec3& p : s.route) {
    a.along.push_back(a.along.back() + (p - a.pts.back()).norm());
    a.pts.push_back(p);
  }
  return a;
}

struct Touch {
  bool any = false;
  std::optional<std::size_t> keep_out;  // the first found (none: a segment the world blocks)
  double last_along_m = 0.0;            // where the last touching segment ends
};

// Does any keep-out touch the route ahead within `window_m`, flown from t_s at v? A segment the
// world blocks or a turn beyond the limit (left by an escape) counts as a touch too.
Touch touches(const Ahead& a, const std::vector<MovingKeepOut>& ko, const SegmentRule& rule, std::optional<Vec3> in,
              double max_turn, double t_s, double v, double window_m) {
  Touch t;
  for (std::size_t i = 1; i < a.pts.size() && a.along[i - 1] < window_m; ++i) {
    const double end = std::min(a.along[i], window_m);
    const Vec3 b = a.at(end);
    const Vec3 seg = a.pts[i] - a.pts[i - 1];
    bool hit =
        !rule(a.pts[i - 1], b) || (in && seg.norm() > 0.0 && turn_rad(*in, seg) > max_turn + kAngleTolerance_rad);
    if (seg.norm() > 0.0) in = seg;
    for (std::size_t k = 0; k < ko.size() && !hit; ++k)
      if (keep_out_distance(ko[k], a.pts[i - 1], t_s + a.along[i - 1] / v, b, t_s + end / v) < ko[k].radius_m) {
        if (!t.any) t.keep_out = k;
        hit = true;
      }
    if (!hit) continue;
    t.any = true;
    t.last_along_m = end;
  }
  return t;
}

bool clear_at(const Vec3& p, double t_s, const std::vector<MovingKeepOut>& ko) {
  for (const MovingKeepOut& k : ko)
    if ((p - k.center_at(t_s)).norm() < k.radius_m) return false;
  return true;
}

std::optional<Vec3> heading_of(const FlightState& s) {
  return s.moved || s.spec->heading_rad ? std::optional<Vec3>(s.direction) : std::nullopt;
}

std::string num(double x) { return strf("%.1f", x); }

std::string describe(const Track& k, double t_s) {
  const double v = k.velocity_mps ? k.velocity_mps->norm() : -1.0;
  if (v >= 0.0) return strf("'%s' (%.1f m/s) at t=%.1f s", k.id.c_str(), v, t_s);
  return strf("'%s' (first seen) at t=%.1f s", k.id.c_str(), t_s);
}

}  // namespace

RollingWindow::RollingWindow(const World& world, RollingWindowOptions options, std::vector<double> windows_m,
                             const std::vector<std::string>& ids)
    : world_(world), opt_(std::move(options)), logs_(windows_m.size()), window_m_(std::move(windows_m)) {
  for (std::size_t i = 0; i < ids.size(); ++i) priority_[ids[i]] = i;
}

void RollingWindow::control(double t, std::span<FlightState> uavs, std::span<const Sensor> sensors) {
  for (std::size_t i = 0; i < uavs.size(); ++i) {
    uavs[i].speed_mps = uavs[i].spec->speed.cruise_mps;  // a hold or an escape lasts one period
    guard(t, i, uavs[i], sensors[i].tracks);
  }
}

std::vector<ThreatDisc> RollingWindow::discs_for(double t, std::size_t i, const FlightState& s,
                                                 const std::vector<Track>& tracks) const {
  // Right of way: of two UAVs in the loop the later gives way, planning around the earlier's
  // disc; the earlier keeps only their bodies apart (both turning wide, each for the other, is
  // how they would meet).
  std::vector<char> gives_way(tracks.size(), 0);
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    const auto it = priority_.find(tracks[k].id);
    gives_way[k] = tracks[k].is_uav && it != priority_.end() && it->second > i;
  }
  return threat_discs(*s.spec, tracks, t, opt_.step_s, opt_.separation_m, gives_way);
}

bool RollingWindow::threatened(double t, std::size_t i, const FlightState& s, const std::vector<Track>& tracks) const {
  const std::vector<ThreatDisc> threats = discs_for(t, i, s, tracks);
  if (s.route.empty() || t + kSameTime_s < s.depart_s) return !clear_to_stay(t, i, s, threats);
  std::vector<MovingKeepOut> discs;
  for (const ThreatDisc& d : threats) discs.push_back(d.disc);
  // At the speed it was given (a formation's slot may fly slower or faster than cruise).
  const double v = s.speed_mps > 1e-9 ? s.speed_mps : s.spec->speed.cruise_mps;
  return touches(ahead_of(s), discs, SegmentRule(world_, *s.spec), heading_of(s), s.spec->max_turn_rad, t, v,
                 window_m_[i])
      .any;
}

bool RollingWindow::guard(double t, std::size_t i, FlightState& s, const std::vector<Track>& tracks) {
  const UavSpec& u = *s.spec;
  RollingWindowLog& log = logs_[i];
  const std::vector<ThreatDisc> threats = discs_for(t, i, s, tracks);
  if (s.route.empty() || t + kSameTime_s < s.depart_s) {  // at its goal, or waiting to depart: keep watch
    if (clear_to_stay(t, i, s, threats)) return false;
    s.route.insert(s.route.begin(), s.position);  // comes back here
    s.depart_s = t;
    const bool escaped = escape(t, s, threats);
    log.escapes += escaped;
    log.events.push_back({t, "", Vec3::Zero(), escaped ? ReplanEvent::Outcome::escaped : ReplanEvent::Outcome::none});
    return true;
  }
  std::vector<MovingKeepOut> discs;
  for (const ThreatDisc& d : threats) discs.push_back(d.disc);
  const Touch touch = touches(ahead_of(s), discs, SegmentRule(world_, u), heading_of(s), u.max_turn_rad, t,
                              u.speed.cruise_mps, window_m_[i]);
  if (!touch.any) return false;
  ReplanEvent ev{t, "", Vec3::Zero()};
  if (touch.keep_out) {
    ev.object = tracks[*touch.keep_out].id;
    ev.velocity_mps = tracks[*touch.keep_out].velocity_mps.value_or(Vec3::Zero());
  }
  std::string why;
  if (replan(t, i, s, threats, ev.velocity_mps, why)) {
    ++log.replans;
    ev.outcome = ReplanEvent::Outcome::replanned;
  } else {
    log.trouble = "no local route " +
                  (touch.keep_out ? "around " + describe(tracks[*touch.keep_out], t)
                                  : "back to its route at t=" + num(t) + " s") +
                  " (" + why + ")";
    if (u.speed.min_mps <= 0.0 && clear_to_stay(t, i, s, threats)) {
      s.speed_mps = 0.0;
      ++log.holds;
      ev.outcome = ReplanEvent::Outcome::held;
    } else if (escape(t, s, threats)) {
      ++log.escapes;
      ev.outcome = ReplanEvent::Outcome::escaped;
    }
  }
  log.events.push_back(ev);
  return true;
}

// The local RRT from where the UAV is to the rejoin point: past the last touch plus one UAV
// step, at the first point clear when the UAV gets there.
bool RollingWindow::replan(double t, std::size_t i, FlightState& s, const std::vector<ThreatDisc>& threats,
                           const Vec3& bias_mps, std::string& why) {
  const UavSpec& u = *s.spec;
  const double v = u.speed.cruise_mps, uav_step = v * opt_.step_s;
  const SegmentRule rule(world_, u);
  const Ahead ahead = ahead_of(s);
  std::vector<MovingKeepOut> discs;
  for (const ThreatDisc& d : threats) discs.push_back(d.disc);
  const Touch touch = touches(ahead, discs, rule, heading_of(s), u.max_turn_rad, t, v, window_m_[i]);
  double join_s = touch.last_along_m + uav_step;
  while (join_s < ahead.along.back()) {
    const Vec3 p = ahead.at(join_s);
    if (rule.point_ok(p) && clear_at(p, t + join_s / v, discs)) break;
    join_s += uav_step;
  }
  join_s = std::min({join_s, ahead.along.back(), next_via_along(ahead, opt_.via_points)});
  std::size_t rest = 0;
  const Vec3 join = ahead.at(join_s, &rest);
  if (rest < ahead.pts.size() && (ahead.pts[rest] - join).norm() <= kSamePoint_m) ++rest;  // joins at a vertex
  if (!clear_at(join, t + join_s / v, discs)) {  // even the goal is taken then: no route can end there
    why = join_s < ahead.along.back() ? "its next via point is inside a disc" : "its goal is inside a disc";
    return false;
  }
  RrtQuery q;
  q.start = s.position;
  q.goal = join;
  q.start_direction = heading_of(s);
  if (rest < ahead.pts.size()) q.goal_direction = ahead.pts[rest] - join;
  q.planar = world_.bounds().extent().z() <= 0.0;
  double reach = 0.5 * (join - s.position).norm();
  for (const MovingKeepOut& k : discs) reach = std::max(reach, 2.0 * k.radius_m);
  q.sample_box = Aabb::of(s.position, join).inflated(reach);
  q.sample_box.min = q.sample_box.min.cwiseMax(world_.bounds().min);
  q.sample_box.max = q.sample_box.max.cwiseMin(world_.bounds().max);
  q.sample_box.max.z() = std::max(q.sample_box.min.z(), std::min(q.sample_box.max.z(), rule.ceiling_m()));
  q.start_time_s = t;
  q.speed_mps = v;
  q.bias_velocity_mps = bias_mps;
  q.uav_step_m = uav_step;
  q.seed = Rng(opt_.seed).split(i * 1000003 + static_cast<std::uint64_t>(std::llround(t / opt_.step_s))).next_u64();
  // Discs the UAV is inside: first it may not come closer; then it may, down to its body plus a
  // quarter of the disc's margin.
  for (const double keep : {1.0, 0.25}) {
    std::vector<MovingKeepOut> planning = discs;
    bool inside = false;
    for (std::size_t k = 0; k < planning.size(); ++k) {
      const double d0 = (s.position - planning[k].center).norm();
      if (d0 >= planning[k].radius_m) continue;
      inside = true;
      const double body = threats[k].body_m;
      planning[k].radius_m =
          std::min(0.999 * d0, keep >= 1.0 ? planning[k].radius_m : body + keep * (planning[k].radius_m - body));
    }
    if (keep < 1.0 && !inside) break;
    q.keep_outs = planning;
    const auto t0 = std::chrono::steady_clock::now();
    const RrtResult r = rrt_search(rule, u.max_turn_rad, q, opt_.local, opt_.stop);
    logs_[i].local_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!r.solved()) {
      why = r.message;
      continue;
    }
    std::vector<Vec3> route(r.path.begin() + 1, r.path.end());
    route.insert(route.end(), ahead.pts.begin() + static_cast<std::ptrdiff_t>(std::min(rest, ahead.pts.size())),
                 ahead.pts.end());
    if (route.empty()) route.push_back(join);
    s.route = std::move(route);
    return true;
  }
  return false;
}

// Whether the UAV's place stays clear of every disc for the window's time.
bool RollingWindow::clear_to_stay(double t, std::size_t i, const FlightState& s,
                                  const std::vector<ThreatDisc>& threats) const {
  // A UAV that gives way plans around this one's place; only what it does in the coming period
  // could still touch it.
  const double window_s = window_m_[i] / s.spec->speed.cruise_mps;
  for (const ThreatDisc& d : threats)
    if (keep_out_distance(d.disc, s.position, t, s.position, t + (d.gives_way ? opt_.step_s : window_s)) <
        d.disc.radius_m)
      return false;
  return true;
}

// The straight flight at top speed (or hovering) that stays farthest from every tracked body
// over the next five periods, flown for one period; false when boxed in by the world.
bool RollingWindow::escape(double t, FlightState& s, const std::vector<ThreatDisc>& threats) const {
  const UavSpec& u = *s.spec;
  const SegmentRule rule(world_, u);
  const double T = opt_.step_s, horizon = 5.0 * T, v = u.speed.max_mps;
  const bool planar = world_.bounds().extent().z() <= 0.0;
  const std::optional<Vec3> heading = heading_of(s);
  const Vec3 onward = s.route.empty() ? Vec3::Zero() : Vec3(s.route.front() - s.position);
  const auto score = [&](const Vec3& velocity) {
    double m = World::kInf;
    for (const ThreatDisc& d : threats)
      m = std::min(m,
                   keep_out_distance(d.disc, s.position, t, s.position + horizon * velocity, t + horizon) - d.body_m);
    return m;
  };
  double best = -World::kInf, best_align = -World::kInf;
  std::optional<Vec3> best_d;
  if (u.speed.min_mps <= 0.0) {
    best = score(Vec3::Zero());
    best_d = Vec3::Zero();
  }
  const int pitches = planar ? 1 : 3;
  for (int pi = 0; pi < pitches; ++pi)
    for (int yi = 0; yi < 24; ++yi) {
      const double pitch = (pi - (pitches - 1) / 2) * std::min(rule.max_climb_rad(), kPi / 6);
      const double yaw = 2.0 * kPi * yi / 24;
      const Vec3 d(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
      if (heading && turn_rad(*heading, d) > u.max_turn_rad) continue;
      if (!rule(s.position, s.position + v * T * d)) continue;
      const double m = score(v * d), align = d.dot(onward);
      if (m > best + 1e-9 || (m > best - 1e-9 && align > best_align)) {
        best = m;
        best_align = align;
        best_d = d;
      }
    }
  if (!best_d) return false;
  if (best_d->squaredNorm() == 0.0) {
    s.speed_mps = 0.0;
    return true;
  }
  std::vector<Vec3> route{s.position + v * T * *best_d};
  route.insert(route.end(), s.route.begin(), s.route.end());
  s.route = std::move(route);
  s.speed_mps = v;
  return true;
}

}  // namespace uavplan
