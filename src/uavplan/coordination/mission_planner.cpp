#include "uavplan/coordination/mission_planner.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "uavplan/coordination/group_planner.h"
#include "uavplan/coordination/rendezvous.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

// Gaps are kept this much above the limit so that rounding in the written plan cannot break them.
constexpr double kTimingMargin_m = 1e-3;

std::string at(const Encounter& e) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "t=%.2f s at (%.1f, %.1f, %.1f)", e.t_s, e.where.x(), e.where.y(), e.where.z());
  return buf;
}

struct Conflict {
  bool any = false;
  std::string what;
};

// UAVs already timed, with their plans.
using Committed = std::vector<std::pair<const UavSpec*, const UavPlan*>>;

Conflict find_conflict(const Scenario& sc, const UavSpec& uav, const Trajectory& tr, const Committed& committed) {
  int idx = -1;
  const Encounter m = closest_moving_approach(sc.world, tr, &idx);
  if (m.distance_m < uav.radius_m + kTimingMargin_m)
    return {true, "moving obstacle '" + sc.world.moving()[idx].id + "' at " + at(m)};
  for (const auto& [spec, other] : committed) {
    const Encounter e = closest_approach(tr, other->trajectory, separation_horizon_s(sc, uav, tr, *spec, other->trajectory));
    if (e.distance_m < required_separation_m(sc, uav, *spec) + kTimingMargin_m)
      return {true, "UAV '" + other->id + "' at " + at(e)};
  }
  return {};
}

void plan_routes(const Scenario& sc, const Planner& planner, const MissionOptions& opt, Plan& plan) {
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    UavPlan up;
    up.id = u.id;
    if (!u.goal) {
      up.message = "no goal given";
    } else {
      Problem pb{u, *u.goal, {}};
      if (sc.mission.type == MissionType::route) pb.via = sc.mission.waypoints;
      pb.seed = opt.seed + i;  // one stream per UAV
      const PlanResult r = planner.plan(pb, sc.world, opt.stop);
      up.status = r.status;
      up.message = r.message;
      up.stats = r.stats;
      up.waypoints = r.route.waypoints;
      up.length_m = r.route.length_m();
    }
    plan.uavs.push_back(std::move(up));
    if (opt.progress) opt.progress(i + 1, sc.uavs.size());
  }
}

// The earliest departure delay, in delay_step_s steps up to max_delay_s, at which the route flown
// at cruise speed keeps clear of the moving obstacles and of the UAVs committed before it; when
// none does, the first conflict met (for the message).
struct Departure {
  bool placed = false;
  double delay_s = 0.0;
  Trajectory trajectory;
  Conflict first;
};
Departure earliest_departure(const Scenario& sc, const UavSpec& u, const std::vector<Vec3>& waypoints, double max_delay_s,
                             const Committed& committed, const MissionOptions& opt) {
  Departure d;
  for (int k = 0; k == 0 || (opt.delay_step_s > 0.0 && k * opt.delay_step_s <= max_delay_s + 1e-9); ++k) {
    const double delay = k * opt.delay_step_s;
    Trajectory tr = time_route(waypoints, u.speed.cruise_mps, delay, opt.max_sample_dt_s);
    const Conflict c = find_conflict(sc, u, tr, committed);
    if (!d.first.any) d.first = c;
    if (c.any) continue;
    d.placed = true;
    d.delay_s = delay;
    d.trajectory = std::move(tr);
    break;
  }
  return d;
}

// Departure delays, in the scenario's UAV order.
void time_routes(const Scenario& sc, const MissionOptions& opt, Plan& plan) {
  double horizon_s = 60.0;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i)
    if (plan.uavs[i].status == Status::solved) horizon_s += 2.0 * plan.uavs[i].length_m / sc.uavs[i].speed.cruise_mps;
  Committed committed;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    UavPlan& up = plan.uavs[i];
    const UavSpec& u = sc.uavs[i];
    if (up.status != Status::solved) continue;
    Departure d = earliest_departure(sc, u, up.waypoints, horizon_s, committed, opt);
    if (!d.placed) {
      up.status = Status::failed;
      up.message = "conflicts with " + d.first.what + " for every departure delay up to " +
                   std::to_string(static_cast<int>(horizon_s)) + " s";
      continue;
    }
    up.trajectory = std::move(d.trajectory);
    up.arrival_s = up.trajectory.back().t_s;
    committed.emplace_back(&u, &up);
  }
}

// A UAV's entry in the plan: solved with its route and trajectory, or failed with the message.
UavPlan flown_plan(const std::string& id, bool ok, std::string message, std::vector<Vec3> waypoints, Trajectory trajectory) {
  UavPlan up;
  up.id = id;
  up.status = ok ? Status::solved : Status::failed;
  up.message = std::move(message);
  if (ok) {
    up.waypoints = std::move(waypoints);
    up.waypoints.erase(std::unique(up.waypoints.begin(), up.waypoints.end()), up.waypoints.end());
    up.length_m = Route{up.waypoints}.length_m();
    up.trajectory = std::move(trajectory);
    up.arrival_s = up.trajectory.back().t_s;
  }
  return up;
}

// P3's group: frame by frame with time-stamped peers, then smoothing.
void plan_group_mission(const Scenario& sc, const ApfOptions& aopt, const MissionOptions& opt, Plan& plan) {
  const GroupResult g = plan_group(sc, aopt, opt.stop);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const GroupUav& r = g.uavs[i];
    const std::string message = r.reached ? "group: " + std::to_string(r.raw.size() - 1) + " frames of " +
                                                std::to_string(g.frame_s) + " s, " + std::to_string(r.smoothed_points) +
                                                " smoothing moves (" + std::to_string(r.kept_points) +
                                                " refused for a conflict)"
                                          : r.message;
    plan.uavs.push_back(flown_plan(r.id, r.reached, message, r.smoothed,
                                   r.reached ? frames_to_trajectory(r.smoothed, g.frame_s) : Trajectory{}));
  }
  if (opt.progress) opt.progress(sc.uavs.size(), sc.uavs.size());
}

// All UAVs depart at once and fly at their cruise speed: equal lengths, equal arrival times. A
// UAV that would come closer than the separation to one timed before it (outside their meeting
// at the goal) departs later instead, in delay_step_s steps, by at most its slack: the time its
// cruise takes over what its length may still grow within the tolerance (shortest + epsilon -
// own), so at equal speeds it arrives within epsilon / speed of the earliest arrival. UAVs are
// timed from the least slack up (scenario order among equals).
// UAVs sharing a stretch of route or converging on the goal then pass one after the other; a
// UAV with no such delay fails with the conflict.
void plan_rendezvous_mission(const Scenario& sc, const DirectionalAStarOptions& dopt, const MissionOptions& opt, Plan& plan) {
  const DirectionalAStarPlanner planner(dopt);
  const RendezvousResult rr = plan_rendezvous(sc, planner, opt.stop);
  const std::size_t n = sc.uavs.size();
  std::vector<UavPlan> planned(n);  // sized once: `committed` points into it
  std::vector<std::string> messages(n);
  std::vector<double> slack_s(n, 0.0);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i) {
    const RendezvousUav& r = rr.uavs[i];
    char buf[200];
    std::snprintf(buf, sizeof buf, "rendezvous: %s, pre-planned %.1f m, final %.1f m (target %.1f m, epsilon %.1f m)",
                  std::string(to_string(r.step)).c_str(), r.preplanned_m, r.final_m, rr.target_m, rr.epsilon_m);
    messages[i] = std::string(buf) + (r.detail.empty() ? "" : "; " + r.detail);
    if (r.ok) order.push_back(i);
    else planned[i] = flown_plan(r.id, false, messages[i], {}, {});
  }
  double shortest_m = World::kInf;
  for (const std::size_t i : order) shortest_m = std::min(shortest_m, rr.uavs[i].final_m);
  for (const std::size_t i : order)
    slack_s[i] = std::max(0.0, shortest_m + rr.epsilon_m - rr.uavs[i].final_m) / sc.uavs[i].speed.cruise_mps;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return slack_s[a] < slack_s[b]; });
  Committed committed;
  for (const std::size_t i : order) {
    const RendezvousUav& r = rr.uavs[i];
    const UavSpec& u = sc.uavs[i];
    Departure d = earliest_departure(sc, u, r.waypoints, slack_s[i], committed, opt);
    char buf[200];
    if (!d.placed) {
      std::snprintf(buf, sizeof buf, " for every departure delay up to %.1f s (its arrival slack)", slack_s[i]);
      planned[i] = flown_plan(r.id, false, messages[i] + "; conflicts with " + d.first.what + buf, {}, {});
      continue;
    }
    if (d.delay_s > 0.0) {
      std::snprintf(buf, sizeof buf, "; departs %.1f s late to keep the separation", d.delay_s);
      messages[i] += buf;
    }
    planned[i] = flown_plan(r.id, true, messages[i], r.waypoints, std::move(d.trajectory));
    committed.emplace_back(&u, &planned[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    plan.uavs.push_back(std::move(planned[i]));
    if (opt.progress) opt.progress(i + 1, n);
  }
}

}  // namespace

double required_separation_m(const Scenario& sc, const UavSpec& a, const UavSpec& b) {
  return std::max(sc.mission.separation_m, a.radius_m + b.radius_m);
}

double separation_horizon_s(const Scenario& sc, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                            const Trajectory& tb) {
  const double need = required_separation_m(sc, a, b);
  if (!a.goal || !b.goal || (*a.goal - *b.goal).norm() >= need || ta.empty() || tb.empty()) return World::kInf;
  // The first time the trajectory comes within `need` of the goal, between samples too (a last
  // sample far out would otherwise leave the approach itself checked).
  auto entering = [&](const Trajectory& tr) {
    if ((tr.front().p - *a.goal).norm() <= need) return tr.front().t_s;
    for (std::size_t k = 1; k < tr.size(); ++k) {
      if ((tr[k].p - *a.goal).norm() > need) continue;
      // |f + s d| = need on this segment, the smaller root: where it enters the sphere.
      const Vec3 d = tr[k].p - tr[k - 1].p, f = tr[k - 1].p - *a.goal;
      const double aa = d.squaredNorm(), bb = f.dot(d), cc = f.squaredNorm() - need * need;
      const double disc = std::max(bb * bb - aa * cc, 0.0);
      const double s = aa > 0.0 ? std::clamp((-bb - std::sqrt(disc)) / aa, 0.0, 1.0) : 1.0;
      return tr[k - 1].t_s + s * (tr[k].t_s - tr[k - 1].t_s);
    }
    return tr.back().t_s;
  };
  return std::min(entering(ta), entering(tb));
}

Plan plan_mission(const Scenario& sc, const MissionOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Plan plan;
  plan.scenario = sc.name;
  plan.algorithm = opt.algorithm.value_or(sc.planner.algorithm);
  plan.seed = opt.seed;
  Params params = sc.planner.params;
  for (const auto& [k, v] : opt.params) params[k] = v;
  if (sc.mission.type == MissionType::rendezvous) {
    // Length control is P4's strategy on directional A*: other planners' parameters do not apply.
    plan.algorithm = "directional_astar";
    if (opt.algorithm.value_or(sc.planner.algorithm) != "directional_astar") params.clear();
    plan_rendezvous_mission(sc, DirectionalAStarOptions::from_params(params), opt, plan);
  }
  if (sc.mission.type == MissionType::group) {
    // P3's group planning is a potential-field method: apf (default) or apf_traditional.
    if (plan.algorithm != "apf" && plan.algorithm != "apf_traditional") {
      plan.algorithm = "apf";
      params.clear();
    }
    plan_group_mission(sc, ApfOptions::from_params(params, plan.algorithm == "apf"), opt, plan);
  }
  const auto planner = make_planner(plan.algorithm, params);

  switch (sc.mission.type) {
    case MissionType::independent:
    case MissionType::route:
      plan_routes(sc, *planner, opt, plan);
      time_routes(sc, opt, plan);
      break;
    case MissionType::rendezvous:
    case MissionType::group:
      break;
    default:
      for (const auto& u : sc.uavs) {
        UavPlan up;
        up.id = u.id;
        up.message = "mission type '" + std::string(to_string(sc.mission.type)) + "' is not supported by planner '" +
                     plan.algorithm + "'";
        plan.uavs.push_back(std::move(up));
      }
  }
  plan.status = combined_status(plan.uavs);
  for (const auto& u : plan.uavs)
    if (u.status != Status::solved && plan.message.empty()) plan.message = u.id + ": " + u.message;
  plan.plan_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return plan;
}

}  // namespace uavplan
