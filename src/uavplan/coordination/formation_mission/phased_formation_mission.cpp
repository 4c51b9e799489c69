#include "uavplan/coordination/formation_mission/phased_formation_mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation_mission/formation_group.h"
#include "uavplan/coordination/formation_mission/landing.h"
#include "uavplan/coordination/timing.h"
#include "uavplan/planning/registry.h"
#include "uavplan/simulation/vehicle_flight.h"

namespace uavplan {
namespace {

constexpr double kG_mps2 = 9.81;

// The model a UAV flies through: its own, or papers.md P5's defaults (time constants; the turn rate of
// a 30 deg bank at cruise; climb at most 20 m/s and within its climb angle at its least speed;
// the horizontal speed at most what leaves the maximum speed in 3-D while climbing).
AutopilotModel mission_model(const UavSpec& u) {
  const AutopilotModel own = autopilot_of(u);
  AutopilotLimits lim = own.limits();
  if (!u.max_turn_rate_rad_s) lim.max_turn_rate_rad_s = kG_mps2 * std::tan(deg_to_rad(30.0)) / u.speed.cruise_mps;
  double climb = u.max_climb_rate_mps.value_or(20.0);
  if (u.max_climb_rad < kPi / 2 - 1e-9)
    climb = std::min(climb, 0.95 * std::max(u.speed.min_mps, 1.0) * std::tan(u.max_climb_rad));
  lim.max_climb_rate_mps = climb;
  // The model holds the horizontal speed; climbing at full rate it must stay within the maximum.
  lim.speed.max_mps = std::sqrt(std::max(0.0, u.speed.max_mps * u.speed.max_mps - climb * climb)) * (1.0 - 1e-6);
  lim.speed.cruise_mps = std::min(lim.speed.cruise_mps, lim.speed.max_mps);
  return AutopilotModel(own.params(), lim);
}

double lift_off_mps(const UavSpec& u) { return std::max(u.speed.min_mps, 0.5 * u.speed.cruise_mps); }

struct GroundRun {
  Trajectory ground;  // parked, taxi to the threshold, take-off roll
  double lift_s = 0.0;
  AutopilotState lift_off;
};

// Take-off in turn, the nearest to the threshold first: each taxis once the one before has begun
// its roll, and lifts off at least takeoff_interval_s after it.
std::vector<GroundRun> departures(const Scenario& sc, const std::vector<Vec3>& starts, const FormationMissionOptions& o,
                                  double dt_s, std::vector<std::size_t>& order) {
  const Airfield& af = *sc.mission.airfield;
  const Vec3 dir(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0);
  const std::size_t n = sc.uavs.size();
  order.resize(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return (starts[a] - af.position).norm() < (starts[b] - af.position).norm();
  });
  std::vector<GroundRun> out(n);
  double prev_lift = -1e300, prev_roll = 0.0;
  for (const std::size_t i : order) {
    const UavSpec& u = sc.uavs[i];
    const double v_lo = lift_off_mps(u);
    const double acc = std::max(3.0, v_lo * v_lo / (2.0 * 0.4 * af.runway_length_m));
    const double roll_s = v_lo / acc, roll_m = 0.5 * v_lo * roll_s;
    const Vec3 thr(af.position.x(), af.position.y(), af.position.z());
    const double taxi_s = (starts[i] - thr).norm() / o.taxi_mps;
    double lift = std::max({prev_lift + o.takeoff_interval_s, taxi_s + roll_s, prev_roll + taxi_s + roll_s});
    lift = std::ceil(lift / dt_s - 1e-9) * dt_s;
    const double roll_start = lift - roll_s, taxi_start = roll_start - taxi_s;
    GroundRun& d = out[i];
    d.ground.push_back({0.0, starts[i]});
    if (taxi_start > 0.0) d.ground.push_back({taxi_start, starts[i]});
    append_straight_run(d.ground, thr, o.taxi_mps, o.taxi_mps, 1.0);
    if (d.ground.back().t_s < roll_start) d.ground.push_back({roll_start, thr});
    const Vec3 lift_at = thr + roll_m * dir;
    append_straight_run(d.ground, lift_at, 0.0, v_lo, 1.0);
    d.lift_s = lift;
    d.lift_off.position = lift_at;
    d.lift_off.speed_mps = v_lo;
    d.lift_off.heading_rad = af.runway_heading_rad;
    prev_lift = lift;
    prev_roll = roll_start;
  }
  return out;
}

}  // namespace

void PhasedFormationMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const FormationMissionOptions o;
  const std::size_t n = sc.uavs.size();
  if (!sc.mission.airfield || sc.mission.shape.size() != n || sc.mission.task_points.empty())
    throw std::invalid_argument("a formation_mission needs an airfield, a slot per UAV and a task point");
  const Airfield& af = *sc.mission.airfield;
  const Vec3 dir(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0);
  std::vector<Vec3> starts;
  std::vector<AutopilotModel> models;
  for (std::size_t i = 0; i < n; ++i) {
    starts.push_back(ctx.ground.start.size() > i && ctx.ground.start[i] ? *ctx.ground.start[i] : sc.uavs[i].start);
    models.push_back(mission_model(sc.uavs[i]));
  }
  FormationGroupOptions go;
  const Topology topology = sc.mission.topology.empty() ? complete_topology(n) : sc.mission.topology;

  // The coarse route (pso_mpc) for a body as wide as the enlarged shape plus the turn's overshoot.
  const UavSpec& lead = sc.uavs.front();
  Vec3 mean_slot = Vec3::Zero();
  for (const Vec3& s : sc.mission.shape) mean_slot += s / static_cast<double>(n);
  double body = 0.0, widest = 0.0, cruise = World::kInf, turn_rate = World::kInf;
  for (std::size_t i = 0; i < n; ++i) {
    body = std::max(body, (sc.mission.shape[i] - mean_slot).head<2>().norm());
    widest = std::max(widest, sc.uavs[i].radius_m);
    cruise = std::min(cruise, sc.uavs[i].speed.cruise_mps);
    turn_rate = std::min(turn_rate, models[i].limits().max_turn_rate_rad_s);
  }
  const double z_form = af.position.z() + o.form_up_height_m;
  const double ceiling =
      lead.ceiling_m ? std::min(*lead.ceiling_m, sc.world.bounds().max.z()) : sc.world.bounds().max.z();
  if (z_form + o.layer_spacing_m * n > ceiling) {
    fail_all(sc, "no room for the form-up's altitude layers below the ceiling", plan);
    return;
  }
  Problem pb;
  pb.uav = lead;
  pb.uav.id = "formation";
  pb.uav.radius_m = o.enlargement * body + widest + cruise / turn_rate * (1.0 - std::cos(deg_to_rad(30.0)));
  pb.uav.start = af.position + (af.runway_length_m + o.departure_after_runway_m) * dir;
  pb.uav.start.z() = z_form;
  pb.uav.heading_rad = af.runway_heading_rad;
  pb.uav.speed.cruise_mps = cruise;
  pb.uav.max_turn_rate_rad_s = 0.8 * turn_rate;  // margin for the shape turning as a body
  pb.uav.model = lead.model.value_or(AutopilotParams{});
  for (const TaskPoint& tp : sc.mission.task_points) {
    pb.via.push_back(tp.position);
    pb.via_entry_heading_rad.push_back(tp.entry_heading_rad);
  }
  // Back to the landing cylinder (phase 5) at the last task point's altitude.
  const Vec3 cylinder = af.position - LandingOptions{}.cylinder_before_threshold_m * dir;
  pb.goal = Vec3(cylinder.x(), cylinder.y(), sc.mission.task_points.back().position.z());
  pb.seed = ctx.options.seed;
  PlanResult route;  // pso_mpc keeps the body (and its turns) inside the bounds too
  try {
    route = make_planner(ctx.algorithm, ctx.params)->plan(pb, sc.world, ctx.options.stop);
  } catch (const std::invalid_argument& e) {
    route.message = e.what();
  }
  if (route.status != Status::solved) {
    fail_all(sc, "the formation's route: " + route.message, plan);
    return;
  }
  const std::vector<Vec3>& wps = route.route.waypoints;
  std::vector<char> fly_over(wps.size(), 0);
  std::size_t last_task = 0;
  for (const TaskPoint& tp : sc.mission.task_points)
    for (std::size_t k = last_task + 1; k < wps.size(); ++k)
      if ((wps[k] - tp.position).norm() < 1.0) {
        fly_over[k] = 1, last_task = k;
        break;
      }
  RouteSteering steer(wps, fly_over, cruise / turn_rate, 300.0);

  // Phase 1: take-off in turn, layers, the enlarged shape, heights, shrink.
  std::vector<std::size_t> order;
  const std::vector<GroundRun> dep = departures(sc, starts, o, go.dt_s, order);
  std::vector<double> layer(n), up(n);
  for (std::size_t k = 0; k < n; ++k)
    layer[order[k]] = o.layer_spacing_m * (static_cast<double>(n - 1 - k) - 0.5 * (n - 1));
  for (std::size_t i = 0; i < n; ++i) up[i] = sc.mission.shape[i].z() - mean_slot.z();
  FormationGroup group(models, sc.mission.shape, topology, go, 0.0);
  FormationOrder order_now;
  order_now.speed_mps = cruise;
  order_now.heading_rad = af.runway_heading_rad;
  order_now.scale = o.enlargement;
  order_now.altitude_m.assign(n, z_form);
  std::vector<double> offsets = layer;
  const auto solo = [&](std::size_t i) {
    return AutopilotCommand{lift_off_mps(sc.uavs[i]), z_form + layer[i], af.runway_heading_rad};
  };
  bool route_left = true;
  const auto step = [&] {
    for (std::size_t i = 0; i < n; ++i) {
      if (!group.flying(i) && dep[i].lift_s <= group.time_s() + 1e-9) group.launch(i, dep[i].lift_off, false);
      // Straight ahead off the runway, into the consensus once clear of the ground.
      if (group.flying(i) && group.state(i).position.z() > af.position.z() + o.join_above_m) group.join(i);
    }
    if (!group.anyone_in_formation()) return group.step(order_now, solo);
    const Vec3 c = group.centroid();
    route_left = steer.update(c);
    // The frame turns towards phi* no faster than the UAVs can (a waypoint passed behind the
    // centroid must not flip the shape through itself).
    const double most = 0.8 * turn_rate * go.dt_s;
    order_now.heading_rad +=
        std::clamp(std::remainder(steer.heading_rad(c) - order_now.heading_rad, 2.0 * kPi), -most, most);
    for (std::size_t i = 0; i < n; ++i) order_now.altitude_m[i] = steer.altitude_m(c) + offsets[i];
    group.step(order_now, solo);
  };
  // A step that has not ended within `limit_s` of flight fails the mission.
  const double route_s = 3.0 * route.route.length_m() / cruise + o.step_timeout_s;
  const auto run_until = [&](const auto& done, double limit_s) {
    const double t0 = group.time_s();
    while (!done()) {
      if (group.time_s() - t0 > limit_s || ctx.options.stop.should_stop()) return false;
      step();
    }
    return true;
  };
  const auto all_joined = [&] {
    for (std::size_t i = 0; i < n; ++i)
      if (!group.in_formation(i)) return false;
    return true;
  };
  const auto in_shape = [&] { return group.shape_error_m(order_now) < o.shape_tolerance_m; };
  FormationLog log;
  std::string failed;
  const auto phase = [&](const char* name, bool ok) {
    if (!ok && failed.empty()) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "the %s phase did not complete (at t = %.0f s the shape was %.1f m off, tolerance %.1f m)", name,
                    group.time_s(), group.shape_error_m(order_now), o.shape_tolerance_m);
      failed = buf;
    }
    log.phases.push_back({name, group.time_s()});
    return ok;
  };
  const auto scale_to = [&](double target) {
    return run_until(
        [&] {
          const double dscale = o.scale_rate_per_s * go.dt_s;
          order_now.scale = order_now.scale < target ? std::min(target, order_now.scale + dscale)
                                                     : std::max(target, order_now.scale - dscale);
          return order_now.scale == target && in_shape();
        },
        o.step_timeout_s);
  };
  bool ok = run_until([&] { return all_joined() && in_shape(); }, o.step_timeout_s);
  if (ok) offsets = up, ok = run_until(in_shape, o.step_timeout_s);
  if (ok) ok = scale_to(1.0);
  // Phases 2 and 3: the route through the task points, then back towards the airfield.
  if (phase("form_up", ok)) ok = run_until([&] { return steer.next() > last_task; }, route_s);
  const auto near_airfield = [&] {
    return !route_left || (group.centroid() - af.position).head<2>().norm() < o.dismiss_within_m;
  };
  if (phase("mission", ok)) ok = run_until(near_airfield, route_s);
  if (phase("return", ok)) {  // phase 4 on the way to the landing cylinder
    ok = scale_to(o.enlargement);
    if (ok) offsets = layer, ok = run_until(in_shape, o.step_timeout_s);
  }
  std::vector<Trajectory> flights(n);
  if (phase("dismiss", ok)) {
    const double t_d = group.time_s();
    for (std::size_t i = 0; i < n; ++i) group.release(i);
    // Phase 5: in turn, the nearest to the landing cylinder first (eq. 2 for each).
    std::vector<std::size_t> land(n);
    std::iota(land.begin(), land.end(), 0);
    const Vec3 centre = af.position - LandingOptions{}.cylinder_before_threshold_m * dir;
    std::stable_sort(land.begin(), land.end(), [&](std::size_t a, std::size_t b) {
      return (group.state(a).position - centre).head<2>().norm() < (group.state(b).position - centre).head<2>().norm();
    });
    std::vector<std::size_t> landed;
    for (const std::size_t i : land) {
      const auto conflicts = [&](const Trajectory& f) {
        for (const std::size_t j : landed)
          if (airfield_encounter(sc, sc.uavs[i], f, sc.uavs[j], flights[j], t_d).conflict) return true;
        return false;
      };
      LandingResult r = plan_landing(af, models[i], group.state(i), t_d, LandingOptions{}, conflicts);
      if (!r.landed) {
        ok = false;
        failed = sc.uavs[i].id + "'s landing: " + r.message;
        break;
      }
      flights[i] = std::move(r.flight);
      landed.push_back(i);
    }
    double end = t_d;
    for (const Trajectory& f : flights)
      if (!f.empty()) end = std::max(end, f.back().t_s);
    log.phases.push_back({"landing", end});
    log.eta_s = end;
  }
  // Each UAV's rows: on the ground, in the group, landing.
  for (std::size_t i = 0; i < n; ++i) {
    Trajectory tr = dep[i].ground;
    for (const TrajectorySample& s : group.trajectory(i))
      if (s.t_s > tr.back().t_s + 1e-9) tr.push_back(s);
    for (const TrajectorySample& s : flights[i])
      if (s.t_s > tr.back().t_s + 1e-9) tr.push_back(s);
    std::vector<Vec3> w{starts[i]};
    w.insert(w.end(), wps.begin(), wps.end());
    w.push_back(tr.back().p);
    plan.uavs.push_back(
        flown_plan(sc.uavs[i].id, ok, ok ? "" : failed, std::move(w), ok ? std::move(tr) : Trajectory{}));
  }
  if (ok)  // in the air the separation, on the ground their bodies (the contract's rule)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const AirfieldEncounter e =
            airfield_encounter(sc, sc.uavs[i], plan.uavs[i].trajectory, sc.uavs[j], plan.uavs[j].trajectory);
        if (!e.conflict) continue;
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.1f m from %s at t = %.1f s, below %.1f m", e.distance_m,
                      sc.uavs[j].id.c_str(), e.t_s, e.need_m);
        for (const std::size_t k : {i, j}) {
          plan.uavs[k].status = Status::failed;
          if (plan.uavs[k].message.empty()) plan.uavs[k].message = k == i ? buf : "too close to " + sc.uavs[i].id;
        }
      }
  plan.formation = log;
}

}  // namespace uavplan
