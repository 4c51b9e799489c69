#include "uavplan/evaluation/verifier.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/contract/task_points.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/ground_legs.h"
#include "uavplan/evaluation/metrics.h"

namespace uavplan {

std::string_view to_string(ViolationKind k) {
  switch (k) {
    case ViolationKind::not_planned:
      return "not_planned";
    case ViolationKind::unknown_uav:
      return "unknown_uav";
    case ViolationKind::trajectory:
      return "trajectory";
    case ViolationKind::start:
      return "start";
    case ViolationKind::goal:
      return "goal";
    case ViolationKind::bounds:
      return "bounds";
    case ViolationKind::ceiling:
      return "ceiling";
    case ViolationKind::obstacle:
      return "obstacle";
    case ViolationKind::low_altitude:
      return "low_altitude";
    case ViolationKind::moving_obstacle:
      return "moving_obstacle";
    case ViolationKind::separation:
      return "separation";
    case ViolationKind::turn:
      return "turn";
    case ViolationKind::climb:
      return "climb";
    case ViolationKind::speed:
      return "speed";
    case ViolationKind::via_point:
      return "via_point";
    case ViolationKind::length_spread:
      return "length_spread";
    case ViolationKind::arrival_spread:
      return "arrival_spread";
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

std::string num(double x) { return num_text(x); }

using Out = std::vector<Violation>;

void add(Out& out, ViolationKind k, const std::string& uav, std::optional<double> t, std::optional<Vec3> p,
         std::string msg) {
  out.push_back({k, uav, t, p, std::move(msg)});
}

// What the clearance at p is measured to, by name: "obstacle hangar" (its id), "obstacle 3 (box)"
// when it has none, or "the terrain".
std::string nearest_thing(const World& w, const Vec3& p) {
  const auto& obstacles = w.obstacles();
  const auto& ids = w.spec().obstacle_ids;
  double best = World::kInf;
  std::string what = "an obstacle";
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const double d = point_distance(obstacles[k], p);
    if (d >= best) continue;
    best = d;
    what = k < ids.size() && !ids[k].empty()
               ? "obstacle " + ids[k]
               : "obstacle " + std::to_string(k) + " (" + std::string(shape_name(obstacles[k])) + ")";
  }
  if (const TerrainGrid* t = w.terrain(); t && t->point_distance(p, best) < best) what = "the terrain";
  return what;
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

void check_uav(const Scenario& sc, const UavSpec& u, const UavPlan& up, double arrival_tolerance_m, Out& out) {
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
  if (u.goal && (tr.back().p - *u.goal).norm() > arrival_tolerance_m + kPositionTolerance_m)
    add(out, ViolationKind::goal, id, tr.back().t_s, tr.back().p,
        arrival_tolerance_m > 0.0
            ? "trajectory does not end within " + num(arrival_tolerance_m) + " m of its shared goal"
            : "trajectory does not end at the goal");
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
  // Segment by segment: timing, speed, static and moving obstacles, height above the ground.
  const GroundLegs legs = ground_legs(sc.world, tr);
  const double keep = keep_off_m(u);
  const std::string keep_text =
      u.clearance_m > 0.0 ? "the UAV radius plus clearance " + num(keep) + " m" : "the UAV radius " + num(keep) + " m";
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
    const bool on_leg = legs.covers(i);
    const double leg_ground = i <= legs.takeoff_end && legs.takeoff ? tr.front().p.z() : tr.back().p.z();
    const double c =
        on_leg ? sc.world.ground_leg_clearance(a.p, b.p, keep, leg_ground) : sc.world.segment_clearance(a.p, b.p, keep);
    if (c < keep - kDistanceTolerance_m) {
      const double f = worst_param(sc.world, a.p, b.p);
      const Vec3 at(a.p + f * (b.p - a.p));
      add(out, ViolationKind::obstacle, id, a.t_s + f * dt, at,
          "clearance " + num(c) + " m to " + nearest_thing(sc.world, at) + ", below " + keep_text);
    }
    if (u.min_agl_m > 0.0 && !on_leg) {
      const double h = sc.world.lowest_height_above_ground(a.p, b.p);
      if (h < u.min_agl_m - kDistanceTolerance_m)
        add(out, ViolationKind::low_altitude, id, a.t_s, a.p,
            "height " + num(h) + " m above the ground, below min_agl " + num(u.min_agl_m) + " m");
    }
  }
  int idx = -1;
  const Encounter m = closest_moving_approach(sc.world, tr, &idx);
  if (m.distance_m < keep - kDistanceTolerance_m)
    add(out, ViolationKind::moving_obstacle, id, m.t_s, m.where,
        "gap " + num(m.distance_m) + " m to moving obstacle '" + sc.world.moving()[idx].id + "', below " + keep_text);
  // Turn and climb on the flown polyline (samples between waypoints are collinear), off the
  // ground legs (a vertical take-off neither climbs within a limit nor keeps a start heading).
  std::vector<Vec3> pts;
  for (std::size_t k = legs.airborne_begin(); k <= legs.airborne_end(tr.size()); ++k) pts.push_back(tr[k].p);
  UavSpec limits = u;
  if (legs.takeoff) limits.heading_rad.reset();
  for (const auto& lv : check_route_limits(pts, limits)) {
    const bool turn = lv.kind == LimitViolation::Kind::turn;
    const auto& s = tr[legs.airborne_begin() + lv.index];
    add(out, turn ? ViolationKind::turn : ViolationKind::climb, id, s.t_s, s.p,
        std::string(turn ? "turn " : "climb ") + num(rad_to_deg(lv.value_rad)) + " deg above the limit " +
            num(rad_to_deg(turn ? u.max_turn_rad : u.max_climb_rad)) + " deg" +
            (turn && lv.index == 0 && u.heading_rad ? " (against the start heading)" : ""));
  }
  // Via points, in order.
  if (sc.mission.type == MissionType::route) {
    const double tol = std::max(u.radius_m, kPositionTolerance_m);
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
      const std::optional<double> entry =
          v < sc.mission.waypoint_entry_heading_rad.size() ? sc.mission.waypoint_entry_heading_rad[v] : std::nullopt;
      if (hit && entry && tr.size() > 1) {  // the heading it arrives with: the row into the point
        const std::size_t k = from <= 1e-9 && seg > 0 ? seg - 1 : seg;
        const Vec3 d = tr[std::min(k + 1, tr.size() - 1)].p - tr[k].p;
        const double off = d.head<2>().norm() > 0.0 ? std::abs(wrap_angle_rad(std::atan2(d.y(), d.x()) - *entry)) : kPi;
        if (off > deg_to_rad(kEntryHeadingTolerance_deg))
          add(out, ViolationKind::via_point, id, tr[k].t_s, via,
              "via point " + std::to_string(v) + " entered at " + num(rad_to_deg(std::atan2(d.y(), d.x()))) + " deg, " +
                  num(rad_to_deg(off)) + " deg off its entry heading " + num(rad_to_deg(*entry)) + " deg");
      }
      if (!hit) {
        add(out, ViolationKind::via_point, id, std::nullopt, via,
            "via point " + std::to_string(v) + " is not visited in order (within " + num(tol) + " m)");
        break;
      }
    }
  }
}

// formation_mission: the task points reached by the formation's reference in order at their
// entry headings, every UAV ending stopped on the runway.
void check_formation_mission(const Scenario& sc, const std::vector<std::pair<const UavSpec*, const UavPlan*>>& flown,
                             Out& out) {
  std::vector<const Trajectory*> trs;
  for (const auto& f : flown) trs.push_back(&f.second->trajectory);
  const std::vector<TaskVisit> visits = task_visits(sc, formation_reference(sc, trs));
  for (std::size_t k = 0; k < sc.mission.task_points.size(); ++k) {
    const TaskPoint& tp = sc.mission.task_points[k];
    if (k < visits.size() && visits[k].reached) continue;
    std::string why = "task point " + std::to_string(k) + " not reached in order by the formation's reference";
    if (k < visits.size() && std::isfinite(visits[k].miss_m))
      why += " (within " + num(tp.radius_m) + " m only " + num(rad_to_deg(visits[k].heading_error_rad)) +
             " deg off its entry heading)";
    add(out, ViolationKind::via_point, "", std::nullopt, tp.position, why);
    break;
  }
  if (!sc.mission.airfield) return;
  const Airfield& af = *sc.mission.airfield;
  const Vec2 along(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad));
  for (const auto& [u, up] : flown) {
    const Vec3 end = up->trajectory.back().p;
    const Vec2 rel = (end - af.position).head<2>();
    const double a = rel.dot(along), off = std::abs(rel.x() * along.y() - rel.y() * along.x());
    if (std::abs(end.z() - af.position.z()) > 1.0 || a < -kPositionTolerance_m ||
        a > af.runway_length_m + kPositionTolerance_m || off > 100.0)
      add(out, ViolationKind::goal, u->id, up->trajectory.back().t_s, end,
          "does not end on the runway (" + num(a) + " m along it, " + num(off) + " m off its centreline, " +
              num(end.z() - af.position.z()) + " m above it)");
  }
}

}  // namespace

std::vector<Violation> verify_plan(const Scenario& sc, const Plan& plan) {
  Out out;
  for (const auto& up : plan.uavs)
    if (!sc.find_uav(up.id))
      add(out, ViolationKind::unknown_uav, up.id, std::nullopt, std::nullopt, "the scenario has no UAV with this id");
  std::vector<std::pair<const UavSpec*, const UavPlan*>> flown;
  const std::vector<Arrival> arrivals = arrival_points(sc);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
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
    check_uav(sc, u, *up, arrivals[i].tolerance_m, out);
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
      if (sc.mission.type == MissionType::formation_mission) {  // the airfield's rule, gone after landing
        const AirfieldEncounter e = airfield_encounter(sc, *ua, pa->trajectory, *ub, pb->trajectory);
        if (e.conflict)
          add(out, ViolationKind::separation, ua->id, e.t_s, e.where,
              "distance " + num(e.distance_m) + " m to '" + ub->id + "', below " + num(e.need_m) + " m" +
                  (e.need_m < need ? " (their bodies, on the ground)" : ""));
        continue;
      }
      const Encounter e = closest_approach(pa->trajectory, pb->trajectory);
      if (e.distance_m < need - kDistanceTolerance_m)
        add(out, ViolationKind::separation, ua->id, e.t_s, e.where,
            "distance " + num(e.distance_m) + " m to '" + ub->id + "', below the separation " + num(need) + " m");
    }
  if (rendezvous && sc.mission.arrival_tolerance_m && flown.size() > 1) {
    double lo = World::kInf, hi = 0.0;
    for (const auto& [u, up] : flown) {
      double len = 0.0;
      for (std::size_t k = 1; k < up->trajectory.size(); ++k)
        len += (up->trajectory[k].p - up->trajectory[k - 1].p).norm();
      lo = std::min(lo, len);
      hi = std::max(hi, len);
    }
    if (hi - lo > *sc.mission.arrival_tolerance_m + kDistanceTolerance_m)
      add(out, ViolationKind::length_spread, "", std::nullopt, std::nullopt,
          "route lengths differ by " + num(hi - lo) + " m, above the tolerance " +
              num(*sc.mission.arrival_tolerance_m) + " m");
  }
  if (sc.mission.type == MissionType::formation_mission) check_formation_mission(sc, flown, out);
  if (sc.mission.type == MissionType::formation && flown.size() > 1) {
    double lo = World::kInf, hi = -World::kInf;
    for (const auto& f : flown)
      lo = std::min(lo, f.second->trajectory.back().t_s), hi = std::max(hi, f.second->trajectory.back().t_s);
    if (hi - lo > sc.mission.arrival_tolerance_s + 1e-6)
      add(out, ViolationKind::arrival_spread, "", std::nullopt, std::nullopt,
          "arrival times differ by " + num(hi - lo) + " s, above arrival_tolerance_s " +
              num(sc.mission.arrival_tolerance_s) + " s");
  }
  return out;
}

std::vector<Violation> finalize_plan(const Scenario& sc, Plan& plan) {
  auto violations = verify_plan(sc, plan);
  for (const auto& v : violations) {
    for (auto& up : plan.uavs) {
      if (up.id != v.uav || up.status != Status::solved) continue;
      up.status = Status::failed;
      up.reason = Reason::rejected;
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
