#include "uavplan/planning/field/apf.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "uavplan/core/geometry.h"
#include "uavplan/core/units.h"
#include "uavplan/planning/field/field_guide.h"
#include "uavplan/planning/segment_rule.h"
#include "uavplan/planning/smoothing/turn_limits.h"

namespace uavplan {

ApfOptions ApfOptions::from_params(const Params& params, ApfField field) {
  ParamReader r(params, field == ApfField::improved ? "apf" : "apf_traditional");
  ApfOptions o = read(r, field);
  r.finish();
  return o;
}

ApfOptions ApfOptions::read(ParamReader& r, ApfField field) {
  const bool improved = field == ApfField::improved;
  ApfOptions o;
  o.improved = improved;
  o.step_m =
      r.number("step_m", o.step_m, 0.0, 1e9, "l, the step per frame, m; 0: derived from the separation and the world");
  o.k_att = r.number("k_att", o.k_att, 1e-9, 1e9, "K_a, the attraction's gain");
  o.r_att_m = r.number("r_att_m", o.r_att_m, 0.0, 1e9, "R_a0, the attraction's cap radius, m; 0: 10 l");
  o.k_rep = r.number("k_rep", o.k_rep, 0.0, 1e12, "K_r, the repulsion's gain; 0: balances the attraction at R_r0 / 2");
  o.r_rep_m =
      r.number("r_rep_m", o.r_rep_m, 0.0, 1e9, "R_r0, the repulsion's reach, m; 0: max(5 l, 2 separation, 3 radius)");
  o.sector_deg = r.number("sector_deg", o.sector_deg, 1.0, 180.0, "the sector rule's half angle, deg (P3: 15)");
  o.max_frames = r.integer("max_frames", o.max_frames, 0, 10'000'000,
                           "frames before giving up; 0: 4 x straight distance / l + 500");
  o.smooth =
      r.boolean("smooth", improved, "P3's triple smoothing afterwards (the traditional field: never)") && improved;
  o.smoothing_threshold_deg = r.number("smoothing_threshold_deg", o.smoothing_threshold_deg, 0.0, 180.0,
                                       "turns under this are smoothed away, deg");
  return o;
}

ApfOptions apf_resolved(const ApfOptions& in, const UavSpec& uav, const World& world) {
  ApfOptions o = in;
  const double extent = world.bounds().extent().norm();
  if (o.step_m <= 0.0)
    o.step_m = std::clamp(0.5 * std::max(o.separation_m, 2.0 * uav.radius_m), extent / 2000.0, extent / 50.0);
  if (o.r_att_m <= 0.0) o.r_att_m = 10.0 * o.step_m;
  if (o.r_rep_m <= 0.0) o.r_rep_m = std::max({5.0 * o.step_m, 2.0 * o.separation_m, 3.0 * uav.radius_m});
  if (o.k_rep <= 0.0) {
    // Repulsion equal to the largest attraction at half the influence distance.
    const double r = 0.5 * o.r_rep_m, inv = 1.0 / r - 1.0 / o.r_rep_m;
    const double shape = o.improved ? std::sqrt(o.r_att_m) * ((1.0 / (r * r)) * inv + inv * inv) : inv / (r * r);
    o.k_rep = o.k_att * o.r_att_m / shape;
  }
  return o;
}

PotentialField::PotentialField(const World& world, const UavSpec& uav, const ApfOptions& resolved)
    : world_(&world), uav_(uav), o_(resolved), inflation_m_(uav.radius_m + kPlanningMargin_m) {}

Vec3 PotentialField::direction(const Vec3& p, const Vec3& goal, std::span<const PeerMotion> peers,
                               const Vec3* aim) const {
  const double big_r = (goal - p).norm();
  if (big_r <= 0.0) return Vec3::Zero();
  const Vec3 to_aim = aim ? Vec3(*aim - p) : Vec3(goal - p);
  const Vec3 pa = to_aim.norm() > 0.0 ? Vec3(to_aim.normalized()) : Vec3((goal - p) / big_r);
  Vec3 force = o_.k_att * (o_.improved ? std::min(big_r, o_.r_att_m) : big_r) * pa;

  // Candidates: (sector, clearance, unit vector from the obstacle to the UAV). The scratch
  // list is per thread, so a step allocates nothing once it has grown.
  struct Source {
    std::int64_t sector;
    double r;
    Vec3 dir;
  };
  thread_local std::vector<Source> sources;
  sources.clear();
  const double w = deg_to_rad(o_.sector_deg);
  auto add = [&](const Vec3& nearest, double clearance) {
    if (clearance >= o_.r_rep_m) return;
    const Vec3 d = p - nearest;
    const double n = d.norm();
    const Vec3 dir = n > 0.0 ? Vec3(d / n) : Vec3(-pa);
    std::int64_t sector = 0;
    if (o_.improved) {
      const Vec3 v = -dir;  // from the UAV to the source
      sector = static_cast<std::int64_t>(std::floor((std::atan2(v.y(), v.x()) + kPi) / w)) * 4096 +
               static_cast<std::int64_t>(std::floor((std::asin(std::clamp(v.z(), -1.0, 1.0)) + kPi / 2) / w));
    }
    sources.push_back({sector, std::max(clearance, 1e-3 * o_.step_m), dir});
  };
  // Following a guide route the static world no longer repels: the route keeps clear of it,
  // and its repulsion is what made the local minimum.
  if (!aim) {
    world_->visit_near(p, o_.r_rep_m + inflation_m_, [&](const Obstacle& ob) {
      const Vec3 c = closest_point(ob, p);
      add(c, (c - p).norm() - uav_.radius_m);
    });
    if (const TerrainGrid* t = world_->terrain()) {
      const double h = t->height_at(p.x(), p.y());
      if (std::isfinite(h)) add(Vec3(p.x(), p.y(), h), p.z() - h - uav_.radius_m);
    }
  }
  // Peers repel only within two steps of their separation: they are obstacles of one frame, and
  // a wider field around UAVs already at their goals walls off the goals between them.
  const double peer_reach = 2.0 * o_.step_m;
  for (const PeerMotion& q : peers) {
    if (aim && q.from == q.to) continue;  // a guided UAV: peers standing still are the route's keep-outs
    const double clearance = (q.to - p).norm() - std::max(o_.separation_m, uav_.radius_m + q.radius_m);
    if (clearance < peer_reach) add(q.to, clearance * o_.r_rep_m / peer_reach);
  }

  // Sector rule (improved field only): the nearest source per sector.
  if (o_.improved && sources.size() > 1) {
    std::sort(sources.begin(), sources.end(), [](const Source& x, const Source& y) {
      return x.sector < y.sector || (x.sector == y.sector && x.r < y.r);
    });
    std::size_t kept = 0;
    for (std::size_t k = 0; k < sources.size(); ++k)
      if (k == 0 || sources[k].sector != sources[k - 1].sector) sources[kept++] = sources[k];
    sources.resize(kept);
  }
  for (const Source& s : sources) {
    const double inv = 1.0 / s.r - 1.0 / o_.r_rep_m;
    const double mag = o_.improved ? o_.k_rep * std::sqrt(big_r) * ((1.0 / (s.r * s.r)) * inv + inv * inv)
                                   : o_.k_rep * inv / (s.r * s.r);
    force += mag * s.dir;
  }
  if (world_->bounds().extent().z() <= 0.0) force.z() = 0.0;  // a 2-D world stays flat
  const double n = force.norm();
  return n > 0.0 ? Vec3(force / n) : pa;
}

bool PotentialField::step_safe(const Vec3& a, const Vec3& b, std::span<const PeerMotion> peers) const {
  if (!world_->in_bounds(b)) return false;
  if ((b - a).norm() > 0.0 && std::abs(pitch_rad(b - a)) > uav_.max_climb_rad + kAngleTolerance_rad) return false;
  if (uav_.ceiling_m && b.z() > *uav_.ceiling_m) return false;
  if (world_->segment_collides(a, b, inflation_m_)) return false;
  for (const PeerMotion& q : peers) {
    const double need = std::max(o_.separation_m, uav_.radius_m + q.radius_m) + kPlanningMargin_m;
    // Both move linearly over the frame: the relative motion's smallest norm.
    if (point_segment_distance(Vec3::Zero(), a - q.from, b - q.to) < need) return false;
  }
  return true;
}

Vec3 PotentialField::step(const Vec3& p, const Vec3& goal, std::span<const PeerMotion> peers, const Vec3* aim) const {
  const double l = o_.step_m;
  if ((goal - p).norm() <= l && step_safe(p, goal, peers)) return goal;
  Vec3 d = direction(p, goal, peers, aim);
  if (d.norm() <= 0.0) return p;
  const bool flat = world_->bounds().extent().z() <= 0.0;
  // Keep the climb limit: a steeper direction is levelled to it.
  const double h = d.head<2>().norm();
  if (!flat && std::atan2(std::abs(d.z()), h) > uav_.max_climb_rad) {
    const double t = std::tan(uav_.max_climb_rad);
    d = h > 0.0 ? Vec3(d.x(), d.y(), std::copysign(t * h, d.z())) : Vec3(1.0, 0.0, std::copysign(t, d.z()));
    d.normalize();
  }
  // The field's step, else the nearest safe direction: rotations about the vertical in
  // 15-degree steps (alternating sides), then tilted up and down in 3-D.
  for (int k = 0; k <= 12; ++k)
    for (int side = (k == 0 ? 1 : -1); side <= 1; side += 2) {
      const double a = side * deg_to_rad(15.0 * k);
      const Vec3 r(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y(), d.z());
      static constexpr double kTilts[] = {0.0, 0.5, -0.5};
      for (int t = 0; t < (flat ? 1 : 3); ++t) {
        Vec3 dir = r + Vec3(0, 0, kTilts[t]);
        dir.normalize();
        if (std::abs(pitch_rad(dir)) > uav_.max_climb_rad + kAngleTolerance_rad) continue;
        const Vec3 q = p + l * dir;
        if (step_safe(p, q, peers)) return q;
      }
    }
  return p;  // hold
}

double FieldFlight::progress_m() const {
  return route_.empty() ? (goal_ - p_).norm() : (route_[next_] - p_).norm() + left_m_[next_];
}

void FieldFlight::follow(std::vector<Vec3> route) {
  route_ = std::move(route);
  left_m_.assign(route_.size(), 0.0);
  for (std::size_t k = route_.size(); k-- > 1;) left_m_[k - 1] = left_m_[k] + (route_[k] - route_[k - 1]).norm();
  next_ = 0;
}

const Vec3& FieldFlight::advance(std::span<const PeerMotion> peers, const Guide& guide,
                                 std::uint64_t keep_out_version) {
  if (arrived_ || failed_) return p_;
  const double l = field_->options().step_m;
  history_.push_back(progress_m());
  if (history_.size() > kWindowFrames && history_[history_.size() - 1 - kWindowFrames] - history_.back() < l) {
    ++stalls_;
    history_.clear();
    auto where = [&] {
      return "(" + std::to_string(p_.x()) + ", " + std::to_string(p_.y()) + ", " + std::to_string(p_.z()) + ")";
    };
    if (guide && (route_.empty() || keep_out_version != route_version_)) {
      // A first route, or the keep-outs changed since the last one: (re)plan from here.
      std::vector<Vec3> r = guide(p_, goal_);
      if (r.empty()) {
        failed_ = true;
        message_ = "stalled near " + where() +
                   " with no route to the goal from there (grid search around the obstacles" + " and the keep-outs)";
        return p_;
      }
      follow(std::move(r));
      route_version_ = keep_out_version;
      stalls_on_route_ = 0;
    } else if (patience_ >= 0 && ++stalls_on_route_ > patience_) {
      failed_ = true;
      message_ = "stalled near " + where() +
                 (route_.empty() ? std::string(" in a local minimum") : " on its escape route") + " after " +
                 std::to_string(stalls_) + " stalls";
      return p_;
    }
  }
  const Vec3* aim = nullptr;
  if (!route_.empty()) {
    // Aim at the first route point more than two steps away, past any within reach now.
    const std::size_t window = std::min(route_.size() - 1, next_ + 16);
    for (std::size_t k = next_; k < window; ++k)
      if ((route_[k] - p_).norm() <= 2.0 * l) next_ = k + 1;
    aim = &route_[next_];
  }
  p_ = field_->step(p_, goal_, peers, aim);
  if (p_ == goal_) arrived_ = true;
  return p_;
}

ApfRun run_apf(const PotentialField& field, const Vec3& start, const Vec3& goal, const FieldFlight::Guide& guide,
               const StopCondition& stop) {
  ApfRun run;
  run.points.push_back(start);
  const ApfOptions& o = field.options();
  const int max_frames =
      o.max_frames > 0 ? o.max_frames : static_cast<int>(4.0 * (goal - start).norm() / o.step_m) + 500;
  // Alone in a static world a stall on the escape route will not pass: two more and it fails.
  FieldFlight flight(field, start, goal, 2);
  std::unique_ptr<FieldGuide> own;
  const FieldFlight::Guide own_guide = [&](const Vec3& from, const Vec3& to) {
    if (!own) own = std::make_unique<FieldGuide>(field.world(), field.uav(), o.step_m, 2'000'000, stop);
    return own->route(from, to, {});
  };
  for (int f = 0; f < max_frames && !flight.arrived(); ++f) {
    if (start == goal) break;
    if ((f & 63) == 0 && stop.should_stop(static_cast<std::uint64_t>(f))) {
      run.message = "stopped before the goal was reached";
      run.reason = Reason::stopped;
      return run;
    }
    flight.advance({}, guide ? guide : own_guide);
    if (flight.failed()) {
      run.message = flight.message();
      return run;
    }
    run.points.push_back(flight.position());
  }
  run.reached = start == goal || flight.arrived();
  if (!run.reached) {
    run.message = "not there within " + std::to_string(max_frames) + " frames; raise planner.params.max_frames";
    run.reason = Reason::budget;
  }
  return run;
}

PlanResult ApfPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult res;
  const ApfOptions o = apf_resolved(options_, pb.uav, world);
  const PotentialField field(world, pb.uav, o);
  std::unique_ptr<FieldGuide> guide_map;  // built at the first stall
  const FieldFlight::Guide guide = [&](const Vec3& from, const Vec3& to) {
    if (!guide_map) guide_map = std::make_unique<FieldGuide>(world, pb.uav, o.step_m, 2'000'000, stop);
    return guide_map->route(from, to, {});
  };
  std::vector<Vec3> stops = pb.via;
  stops.push_back(pb.goal);
  Vec3 from = pb.uav.start;
  res.route.waypoints.push_back(from);
  for (std::size_t leg = 0; leg < stops.size(); ++leg) {
    const Vec3& target = stops[leg];
    const ApfRun run = run_apf(field, from, target, guide, stop);
    res.route.waypoints.insert(res.route.waypoints.end(), run.points.begin() + 1, run.points.end());
    if (!run.reached) {
      res.message = leg_name(leg, stops.size() + 1) + ": " + run.message;
      res.reason = run.reason;
      res.route.waypoints.clear();
      return res;
    }
    from = target;
  }
  // Repeated points (holds) carry no direction; then P3's smoothing (a move that would touch an
  // obstacle is refused), then the turn limits, as for every planner.
  // The via points are pinned before the smoothing, which moves no pinned point (a sharp turn at
  // a via point would otherwise pull the route off it).
  auto& pts = res.route.waypoints;
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  std::vector<char> pinned(pts.size(), 0);
  pinned.front() = pinned.back() = 1;
  for (std::size_t i = 0, v = 0; i < pts.size() && v < pb.via.size(); ++i)
    if (pts[i] == pb.via[v]) pinned[i] = 1, ++v;
  if (o.smooth) {
    smooth_triples(pts, deg_to_rad(o.smoothing_threshold_deg), [&](std::size_t i, const Vec3& c) {
      return !pinned[i] && field.step_safe(pts[i - 1], c, {}) && field.step_safe(c, pts[i + 1], {});
    });
  }
  const SegmentRule rule(world, pb.uav);
  const TurnShaping shaped =
      enforce_turn_limits(pts, pinned, pb.uav.heading_rad, {pb.uav.max_turn_rad, pb.uav.max_climb_rad}, rule);
  if (!shaped.solved()) {
    res.fail(shaped.reason, "turn limits: " + shaped.message);
    pts.clear();
    return res;
  }
  pts = shaped.waypoints;
  res.status = Status::solved;
  return res;
}

}  // namespace uavplan
