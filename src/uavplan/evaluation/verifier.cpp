#include "uavplan/evaluation/verifier.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "uavplan/coordination/separation.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/metrics.h"

namespace uavplan {

std::string_view to_string(ViolationKind k) {
  switch (k) {
    case ViolationKind::not_planned: return "not_planned";
    case ViolationKind::unknown_uav: return "unknown_uav";
    case ViolationKind::trajectory: return "trajectory";
    case ViolationKind::start: return "start";
    case ViolationKind::goal: return "goal";
    case ViolationKind::bounds: return "bounds";
    case ViolationKind::ceiling: return "ceiling";
    case ViolationKind::obstacle: return "obstacle";
    case ViolationKind::moving_obstacle: return "moving_obstacle";
    case ViolationKind::separation: return "separation";
    case ViolationKind::turn: return "turn";
    case ViolationKind::climb: return "climb";
    case ViolationKind::speed: return "speed";
    case ViolationKind::via_point: return "via_point";
    case ViolationKind::length_spread: return "length_spread";
  }
  return "?";
}

std::string describe(const Violation& v) {
  std::string s = v.uav.empty() ? std::string("mission") : v.uav;
  s += " ";
  s += to_string(v.kind);
  char buf[160];
  if (v.t_s) {
    std::snprintf(buf, sizeof buf, " t=%.2f s", *v.t_s);
    s += buf;
  }
  if (v.where) {
    std::snprintf(buf, sizeof buf, " at (%.2f, %.2f, %.2f)", v.where->x(), v.where->y(), v.where->z());
    s += buf;
  }
  return s + ": " + v.message;
}

namespace {

std::string num(double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

using Out = std::vector<Violation>;

void add(Out& out, ViolationKind k, const std::string& uav, std::optional<double> t, std::optional<Vec3> p,
         std::string msg) {
  out.push_back({k, uav, t, p, std::move(msg)});
}

// Where along a segment the clearance is smallest (for the report only).
double worst_param(const World& w, const Vec3& a, const Vec3& b) {
  double best_t = 0.0, best = World::kInf;
  for (int i = 0; i <= 32; ++i) {
    const double t = i / 32.0;
    const double c = w.clearance(a + t * (b - a), best);
    if (c < best) {
      best = c;
      best_t = t;
    }
  }
  return best_t;
}

void check_uav(const Scenario& sc, const UavSpec& u, const UavPlan& up, Out& out) {
  const auto& tr = up.trajectory;
  const std::string& id = u.id;
  for (const auto& s : tr)
    if (!std::isfinite(s.t_s) || !s.p.allFinite()) {
      add(out, ViolationKind::trajectory, id, std::nullopt, std::nullopt, "non-finite trajectory row");
      return;
    }
  // Start and goal.
  if ((tr.front().p - u.start).norm() > kPositionTolerance_m)
    add(out, ViolationKind::start, id, tr.front().t_s, tr.front().p, "trajectory does not begin at the start");
  if (u.goal && (tr.back().p - *u.goal).norm() > kPositionTolerance_m)
    add(out, ViolationKind::goal, id, tr.back().t_s, tr.back().p, "trajectory does not end at the goal");
  const double ceiling = u.ceiling_m ? std::min(*u.ceiling_m, sc.world.bounds().max.z()) : sc.world.bounds().max.z();
  const Aabb bounds = sc.world.bounds().inflated(kDistanceTolerance_m);
  bool reported_bounds = false, reported_ceiling = false;
  for (const auto& s : tr) {
    if (!reported_bounds && !bounds.contains(s.p)) {
      add(out, ViolationKind::bounds, id, s.t_s, s.p, "outside the world bounds");
      reported_bounds = true;
    }
    if (!reported_ceiling && s.p.z() > ceiling + kDistanceTolerance_m) {
      add(out, ViolationKind::ceiling, id, s.t_s, s.p, "above the ceiling " + num(ceiling) + " m");
      reported_ceiling = true;
    }
  }
  // Segment by segment: timing, speed, static and moving obstacles.
  const double r = u.radius_m;
  for (std::size_t i = 1; i < tr.size(); ++i) {
    const auto &a = tr[i - 1], &b = tr[i];
    const double dt = b.t_s - a.t_s, len = (b.p - a.p).norm();
    if (dt < 0.0 || (dt == 0.0 && len > kPositionTolerance_m)) {
      add(out, ViolationKind::trajectory, id, a.t_s, a.p, dt < 0.0 ? "time goes backwards" : "position jumps");
      continue;
    }
    if (dt > 0.0 && len / dt > u.speed.max_mps * (1.0 + 1e-6) + 1e-9)
      add(out, ViolationKind::speed, id, a.t_s, a.p,
          "speed " + num(len / dt) + " m/s above the maximum " + num(u.speed.max_mps) + " m/s");
    const double c = sc.world.segment_clearance(a.p, b.p, r);
    if (c < r - kDistanceTolerance_m) {
      const double f = worst_param(sc.world, a.p, b.p);
      add(out, ViolationKind::obstacle, id, a.t_s + f * dt, Vec3(a.p + f * (b.p - a.p)),
          "clearance " + num(c) + " m to an obstacle or the terrain, below the UAV radius " + num(r) + " m");
    }
  }
  int idx = -1;
  const Encounter m = closest_moving_approach(sc.world, tr, &idx);
  if (m.distance_m < r - kDistanceTolerance_m)
    add(out, ViolationKind::moving_obstacle, id, m.t_s, m.where,
        "gap " + num(m.distance_m) + " m to moving obstacle '" + sc.world.moving()[idx].id +
            "', below the UAV radius " + num(r) + " m");
  // Turn and climb on the flown polyline (samples between waypoints are collinear).
  std::vector<Vec3> pts;
  for (const auto& s : tr) pts.push_back(s.p);
  for (const auto& lv : check_route_limits(pts, u)) {
    const bool turn = lv.kind == LimitViolation::Kind::turn;
    const auto& s = tr[lv.index];
    add(out, turn ? ViolationKind::turn : ViolationKind::climb, id, s.t_s, s.p,
        std::string(turn ? "turn " : "climb ") + num(rad_to_deg(lv.value_rad)) + " deg above the limit " +
            num(rad_to_deg(turn ? u.max_turn_rad : u.max_climb_rad)) + " deg" +
            (turn && lv.index == 0 && u.heading_rad ? " (against the start heading)" : ""));
  }
  // Via points, in order.
  if (sc.mission.type == MissionType::route) {
    const double tol = std::max(r, kPositionTolerance_m);
    std::size_t seg = 0;
    double from = 0.0;  // progress so far: segment `seg`, this fraction along it
    for (std::size_t v = 0; v < sc.mission.waypoints.size(); ++v) {
      const Vec3& via = sc.mission.waypoints[v];
      bool hit = tr.size() == 1 && (tr[0].p - via).norm() <= tol;
      for (; !hit && seg + 1 < tr.size(); ++seg, from = 0.0) {
        const Vec3 a = tr[seg].p + from * (tr[seg + 1].p - tr[seg].p);
        double t = 0.0;
        if (point_segment_distance(via, a, tr[seg + 1].p, &t) <= tol) {
          from += t * (1.0 - from);
          hit = true;
          break;
        }
      }
      if (!hit) {
        add(out, ViolationKind::via_point, id, std::nullopt, via,
            "via point " + std::to_string(v) + " is not visited in order (within " + num(tol) + " m)");
        break;
      }
    }
  }
}

}  // namespace

std::vector<Violation> verify_plan(const Scenario& sc, const Plan& plan) {
  Out out;
  for (const auto& up : plan.uavs)
    if (!sc.find_uav(up.id))
      add(out, ViolationKind::unknown_uav, up.id, std::nullopt, std::nullopt, "the scenario has no UAV with this id");
  std::vector<std::pair<const UavSpec*, const UavPlan*>> flown;
  for (const auto& u : sc.uavs) {
    const UavPlan* up = plan.find_uav(u.id);
    if (!up) {
      add(out, ViolationKind::not_planned, u.id, std::nullopt, std::nullopt, "missing from the plan");
      continue;
    }
    if (up->trajectory.empty()) {
      add(out, ViolationKind::not_planned, u.id, std::nullopt, std::nullopt,
          "no trajectory" + (up->message.empty() ? std::string() : " (" + up->message + ")"));
      continue;
    }
    check_uav(sc, u, *up, out);
    flown.emplace_back(&u, up);
  }
  const bool rendezvous = sc.mission.type == MissionType::rendezvous;
  std::vector<const Trajectory*> trs;
  for (const auto& f : flown) trs.push_back(&f.second->trajectory);
  const SweptBoxes boxes(trs);  // pairs never near enough to conflict are skipped
  for (std::size_t i = 0; i < flown.size(); ++i)
    for (std::size_t j = i + 1; j < flown.size(); ++j) {
      const auto& [ua, pa] = flown[i];
      const auto& [ub, pb] = flown[j];
      const double need = required_separation_m(sc, *ua, *ub);
      if (boxes.lower_bound_m(i, j) >= need) continue;
      // UAVs sent to one goal meet there by design (separation_horizon_s).
      const double t_max = separation_horizon_s(sc, *ua, pa->trajectory, *ub, pb->trajectory);
      const Encounter e = closest_approach(pa->trajectory, pb->trajectory, t_max);
      if (e.distance_m < need - kDistanceTolerance_m)
        add(out, ViolationKind::separation, ua->id, e.t_s, e.where,
            "distance " + num(e.distance_m) + " m to '" + ub->id + "', below the separation " + num(need) + " m");
    }
  if (rendezvous && sc.mission.arrival_tolerance_m && flown.size() > 1) {
    double lo = World::kInf, hi = 0.0;
    for (const auto& [u, up] : flown) {
      double len = 0.0;
      for (std::size_t k = 1; k < up->trajectory.size(); ++k) len += (up->trajectory[k].p - up->trajectory[k - 1].p).norm();
      lo = std::min(lo, len);
      hi = std::max(hi, len);
    }
    if (hi - lo > *sc.mission.arrival_tolerance_m + kDistanceTolerance_m)
      add(out, ViolationKind::length_spread, "", std::nullopt, std::nullopt,
          "route lengths differ by " + num(hi - lo) + " m, above the tolerance " + num(*sc.mission.arrival_tolerance_m) + " m");
  }
  return out;
}

std::vector<Violation> finalize_plan(const Scenario& sc, Plan& plan) {
  auto violations = verify_plan(sc, plan);
  for (const auto& v : violations) {
    for (auto& up : plan.uavs) {
      if (up.id != v.uav || up.status != Status::solved) continue;
      up.status = Status::failed;
      up.message = "verification: " + describe(v);
    }
  }
  plan.status = combined_status(plan.uavs);
  // A mission-level violation (length spread) fails the whole plan.
  for (const auto& v : violations)
    if (v.uav.empty()) {
      plan.status = Status::failed;
      plan.message = "verification: " + describe(v);
    }
  if (plan.message.empty())
    for (const auto& up : plan.uavs)
      if (up.status != Status::solved) {
        plan.message = up.id + ": " + up.message;
        break;
      }
  compute_metrics(sc, plan);
  return violations;
}

}  // namespace uavplan
