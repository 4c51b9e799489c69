#include "uavplan/evaluation/verifier.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/mission.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/ground_legs.h"
#include "uavplan/evaluation/metrics.h"

namespace uavplan {

namespace {

// What a UAV keeps off obstacles and movers, in words: "the UAV radius 0.5 m", or "the UAV
// radius plus clearance 2.5 m".
std::string keep_off_text(const UavSpec& u) {
  return (u.clearance_m > 0.0 ? "the UAV radius plus clearance " : "the UAV radius ") + num_text(keep_off_m(u)) + " m";
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

// A UAV with a home flies from it to its start, on to its goal, and back to it.
void check_home_flight(const UavSpec& u, const Trajectory& tr, double arrival_tolerance_m, Violations& out) {
  if ((tr.front().p - *u.home).norm() > kPositionTolerance_m)
    add_violation(out, ViolationKind::start, u.id, tr.front().t_s, tr.front().p,
                  "trajectory does not begin at its home");
  if ((tr.back().p - *u.home).norm() > kPositionTolerance_m)
    add_violation(out, ViolationKind::goal, u.id, tr.back().t_s, tr.back().p, "trajectory does not end at its home");
  const double tol = std::max(u.radius_m, kPositionTolerance_m);
  TrackProgress at;
  if (!passes_within(tr, u.start, tol, at))
    add_violation(out, ViolationKind::start, u.id, std::nullopt, u.start,
                  "does not pass its start (within " + num_text(tol) + " m) after taking off from home");
  else if (u.goal && !passes_within(tr, *u.goal, std::max(tol, arrival_tolerance_m), at))
    add_violation(out, ViolationKind::goal, u.id, std::nullopt, *u.goal,
                  "does not pass its goal after its start before landing at home");
}

// The rows themselves: finite, from the start to the goal, inside the bounds and below the
// ceiling. False when they are not numbers at all (nothing else can be checked).
bool check_rows(const Scenario& sc, const UavSpec& u, const Trajectory& tr, double arrival_tolerance_m,
                Violations& out) {
  const std::string& id = u.id;
  for (const auto& s : tr)
    if (!std::isfinite(s.t_s) || !s.p.allFinite()) {
      add_violation(out, ViolationKind::trajectory, id, std::nullopt, std::nullopt, "non-finite trajectory row");
      return false;
    }
  if (u.home) {
    check_home_flight(u, tr, arrival_tolerance_m, out);
  } else if ((tr.front().p - u.start).norm() > kPositionTolerance_m) {
    add_violation(out, ViolationKind::start, id, tr.front().t_s, tr.front().p,
                  "trajectory does not begin at the start");
  }
  if (!u.home && u.goal && (tr.back().p - *u.goal).norm() > arrival_tolerance_m + kPositionTolerance_m)
    add_violation(out, ViolationKind::goal, id, tr.back().t_s, tr.back().p,
                  arrival_tolerance_m > 0.0
                      ? "trajectory does not end within " + num_text(arrival_tolerance_m) + " m of its shared goal"
                      : "trajectory does not end at the goal");
  const double ceiling = u.ceiling_m ? std::min(*u.ceiling_m, sc.world.bounds().max.z()) : sc.world.bounds().max.z();
  const Aabb bounds = sc.world.bounds().inflated(kDistanceTolerance_m);
  bool reported_bounds = false, reported_ceiling = false;
  for (const auto& s : tr) {
    if (!reported_bounds && !bounds.contains(s.p)) {
      add_violation(out, ViolationKind::bounds, id, s.t_s, s.p, "outside the world bounds");
      reported_bounds = true;
    }
    if (!reported_ceiling && s.p.z() > ceiling + kDistanceTolerance_m) {
      add_violation(out, ViolationKind::ceiling, id, s.t_s, s.p, "above the ceiling " + num_text(ceiling) + " m");
      reported_ceiling = true;
    }
  }
  return true;
}

// Segment by segment: timing, speed, static obstacles and height above the ground.
void check_segments(const Scenario& sc, const UavSpec& u, const Trajectory& tr, const GroundLegs& legs,
                    Violations& out) {
  const std::string& id = u.id;
  const double keep = keep_off_m(u);
  const std::string keep_text = keep_off_text(u);
  for (std::size_t i = 1; i < tr.size(); ++i) {
    const auto &a = tr[i - 1], &b = tr[i];
    const double dt = b.t_s - a.t_s, len = (b.p - a.p).norm();
    if (dt < 0.0 || (dt == 0.0 && len > kPositionTolerance_m)) {
      add_violation(out, ViolationKind::trajectory, id, a.t_s, a.p,
                    dt < 0.0 ? "time goes backwards" : "position jumps");
      continue;
    }
    if (dt > 0.0 && len / dt > u.speed.max_mps * (1.0 + 1e-6) + 1e-9)
      add_violation(out, ViolationKind::speed, id, a.t_s, a.p,
                    "speed " + num_text(len / dt) + " m/s above the maximum " + num_text(u.speed.max_mps) + " m/s");
    const bool on_leg = legs.covers(i);
    const double leg_ground = i <= legs.takeoff_end && legs.takeoff ? tr.front().p.z() : tr.back().p.z();
    const double c =
        on_leg ? sc.world.ground_leg_clearance(a.p, b.p, keep, leg_ground) : sc.world.segment_clearance(a.p, b.p, keep);
    if (c < keep - kDistanceTolerance_m) {
      const double f = worst_param(sc.world, a.p, b.p);
      const Vec3 at(a.p + f * (b.p - a.p));
      add_violation(out, ViolationKind::obstacle, id, a.t_s + f * dt, at,
                    "clearance " + num_text(c) + " m to " + sc.world.nearest_label(at) + ", below " + keep_text);
    }
    if (u.min_agl_m > 0.0 && !on_leg) {
      const double h = sc.world.lowest_height_above_ground(a.p, b.p);
      if (h < u.min_agl_m - kDistanceTolerance_m)
        add_violation(out, ViolationKind::low_altitude, id, a.t_s, a.p,
                      "height " + num_text(h) + " m above the ground, below min_agl " + num_text(u.min_agl_m) + " m");
    }
    if (u.max_agl_m && !on_leg) {
      const double h = sc.world.highest_height_above_ground(a.p, b.p);
      if (h > *u.max_agl_m + kDistanceTolerance_m)
        add_violation(out, ViolationKind::high_altitude, id, a.t_s, a.p,
                      "height " + num_text(h) + " m above the lowest ground under it, above max_agl " +
                          num_text(*u.max_agl_m) + " m");
    }
  }
}

void check_moving(const Scenario& sc, const UavSpec& u, const Trajectory& tr, Violations& out) {
  const double keep = keep_off_m(u);
  int idx = -1;
  const Encounter m = closest_moving_approach(sc.world, tr, &idx);
  if (m.distance_m < keep - kDistanceTolerance_m)
    add_violation(out, ViolationKind::moving_obstacle, u.id, m.t_s, m.where,
                  "gap " + num_text(m.distance_m) + " m to moving obstacle '" + sc.world.moving()[idx].id +
                      "', below " + keep_off_text(u));
}

// Turn and climb on the flown polyline (samples between waypoints are collinear), off the
// ground legs (a vertical take-off neither climbs within a limit nor keeps a start heading).
void check_limits(const UavSpec& u, const Trajectory& tr, const GroundLegs& legs, Violations& out) {
  std::vector<Vec3> pts;
  for (std::size_t k = legs.airborne_begin(); k <= legs.airborne_end(tr.size()); ++k) pts.push_back(tr[k].p);
  UavSpec limits = u;
  if (legs.takeoff) limits.heading_rad.reset();
  for (const auto& lv : check_route_limits(pts, limits)) {
    const bool turn = lv.kind == LimitViolation::Kind::turn;
    const auto& s = tr[legs.airborne_begin() + lv.index];
    add_violation(out, turn ? ViolationKind::turn : ViolationKind::climb, u.id, s.t_s, s.p,
                  std::string(turn ? "turn " : "climb ") + num_text(rad_to_deg(lv.value_rad)) +
                      " deg above the limit " + num_text(rad_to_deg(turn ? u.max_turn_rad : u.max_climb_rad)) + " deg" +
                      (turn && lv.index == 0 && u.heading_rad ? " (against the start heading)" : ""));
  }
}

// Every rule of one UAV's flight; the mission adds its own.
void check_uav(const Scenario& sc, const Mission& mission, const UavSpec& u, const Trajectory& tr,
               double arrival_tolerance_m, Violations& out) {
  if (!check_rows(sc, u, tr, arrival_tolerance_m, out)) return;
  const GroundLegs legs = ground_legs(sc.world, tr);
  check_segments(sc, u, tr, legs, out);
  check_moving(sc, u, tr, out);
  check_limits(u, tr, legs, out);
  mission.check_uav(sc, u, tr, out);
}

// Separation of every pair the swept boxes do not rule out, by the mission's rule.
void check_pairs(const Scenario& sc, const Mission& mission, const FlownUavs& flown, Violations& out) {
  std::vector<const Trajectory*> trs;
  for (const auto& f : flown) trs.push_back(&f.second->trajectory);
  // Pairs never near enough to conflict are skipped: no pair needs more than the separation or
  // twice the largest body, so only the pairs within that are checked, in (i, j) order.
  double widest_m = 0.0;
  for (const auto& f : flown) widest_m = std::max(widest_m, f.first->radius_m);
  const double reach_m = std::max(sc.mission.separation_m, 2.0 * widest_m);
  for (const SweptBoxes::NearPair& near : SweptBoxes(trs).pairs_within(reach_m)) {
    const auto& [ua, pa] = flown[near.i];
    const auto& [ub, pb] = flown[near.j];
    const double need = required_separation_m(sc, *ua, *ub);
    if (near.bound_m >= need) continue;
    mission.check_pair(sc, *ua, pa->trajectory, *ub, pb->trajectory, need, out);
  }
}

}  // namespace

std::vector<Violation> verify_plan(const Scenario& sc, const Plan& plan) {
  Violations out;
  const Mission* mission = find_mission(sc.mission.type);
  if (!mission) throw std::invalid_argument("no mission registered for type " + sc.mission.type);
  for (const auto& up : plan.uavs)
    if (!sc.find_uav(up.id))
      add_violation(out, ViolationKind::unknown_uav, up.id, std::nullopt, std::nullopt,
                    "the scenario has no UAV with this id");
  FlownUavs flown;
  const std::vector<Arrival> arrivals = arrival_points(sc);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    const UavPlan* up = plan.find_uav(u.id);
    if (!up) {
      add_violation(out, ViolationKind::not_planned, u.id, std::nullopt, std::nullopt, "missing from the plan");
      continue;
    }
    if (up->trajectory.empty()) {
      add_violation(out, ViolationKind::not_planned, u.id, std::nullopt, std::nullopt,
                    "no trajectory" + (up->message.empty() ? std::string() : " (" + up->message + ")"));
      continue;
    }
    check_uav(sc, *mission, u, up->trajectory, arrivals[i].tolerance_m, out);
    flown.emplace_back(&u, up);
  }
  check_pairs(sc, *mission, flown, out);
  mission->check_plan(sc, flown, out);
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
  // A mission-level violation (length spread) fails the whole plan.
  for (const auto& v : violations)
    if (v.uav.empty()) plan.message = "verification: " + describe(v);
  combine_outcomes(plan);
  for (const auto& v : violations)
    if (v.uav.empty()) {
      plan.status = Status::failed;
      plan.reason = Reason::rejected;
    }
  compute_metrics(sc, plan);
  return violations;
}

}  // namespace uavplan
