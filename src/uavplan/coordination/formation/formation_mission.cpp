#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation/formation_flight.h"
#include "uavplan/coordination/routes/local_layer.h"
#include "uavplan/coordination/timing.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

Vec3 centroid(const std::vector<Vec3>& pts) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p / static_cast<double>(pts.size());
  return c;
}

// The reference's route: for a body as wide as the shape, else for the widest UAV alone.
PlanResult reference_route(const Scenario& sc, const MissionContext& ctx, const Vec3& from, const Vec3& to) {
  const auto planner = make_planner(ctx.algorithm, ctx.params);
  const Vec3 c = centroid(formation_shape(sc));
  double body = 0.0, widest = 0.0;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    body = std::max(body, (formation_shape(sc)[i] - c).norm() + sc.uavs[i].radius_m);
    widest = std::max(widest, sc.uavs[i].radius_m);
  }
  Problem pb;
  pb.uav = sc.uavs.front();
  pb.uav.id = "formation";
  pb.uav.start = from;
  pb.goal = to;
  pb.seed = ctx.options.seed;
  PlanResult r;
  for (const double radius : {body, widest}) {
    pb.uav.radius_m = radius;
    try {
      r = planner->plan(pb, sc.world, ctx.options.stop);
    } catch (const std::invalid_argument& e) {  // the reference's start or goal has no room for the shape
      r.status = Status::failed;
      r.message = e.what();
    }
    if (r.status == Status::solved) return r;
  }
  return r;
}

std::vector<double> windows_of(const Scenario& sc, const LocalLayer& layer) {
  std::vector<double> w;
  for (const UavSpec& u : sc.uavs)
    w.push_back(layer.window_m > 0.0 ? layer.window_m
                : u.sensor_range_m
                    ? *u.sensor_range_m
                    : 10.0 * sc.mission.step_s * u.speed.cruise_mps);  // known in advance: ten periods ahead
  return w;
}

// The first and the last of the solved UAVs to arrive (contract: at the goal to stay).
struct ArrivalSpread {
  const UavPlan* first = nullptr;
  const UavPlan* last = nullptr;
  double s() const { return first ? last->arrival_s - first->arrival_s : 0.0; }
};
ArrivalSpread arrival_spread(const Plan& plan) {
  ArrivalSpread a;
  for (const UavPlan& up : plan.uavs) {
    if (up.status != Status::solved || !std::isfinite(up.arrival_s)) continue;
    if (!a.first || up.arrival_s < a.first->arrival_s) a.first = &up;
    if (!a.last || up.arrival_s > a.last->arrival_s) a.last = &up;
  }
  return a;
}

// The approach to the goals (formation_schedule.h): one period's flight, and at least four
// arrival radii, so that no UAV is within its arrival radius before the formation comes in.
double approach_m(const Scenario& sc, double cruise_mps) {
  const std::vector<Arrival> arrivals = arrival_points(sc);
  double widest = 0.0;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) widest = std::max(widest, arrival_radius_m(sc.uavs[i], arrivals[i]));
  return std::max(cruise_mps * sc.mission.step_s, 4.0 * widest);
}

// What they flew must keep clear of everything that moves and of each other, and arrive within
// the tolerance of one another (`spread`, of the UAVs solved so far); if not, the plan names the
// first and the last to arrive.
void check_flown(const Scenario& sc, const ArrivalSpread& spread, Plan& plan) {
  Committed all;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) all.emplace_back(&sc.uavs[i], &plan.uavs[i]);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    UavPlan& up = plan.uavs[i];
    if (up.status != Status::solved) continue;
    Committed others;
    for (const auto& c : all)
      if (c.second != &up) others.push_back(c);
    const Conflict c = find_conflict(sc, sc.uavs[i], up.trajectory, others);
    if (c.any) {
      up.status = Status::failed;
      up.reason = Reason::conflict;
      up.message = "could not avoid " + c.what;
    }
  }
  if (spread.s() <= formation_section(sc).arrival_tolerance_s + kSameTime_s) return;
  const std::string buf = strf(
      "arrivals %.1f s apart ('%s' at its goal at %.1f s, '%s' at %.1f s), more than "
      "arrival_tolerance_s = %g s: '%s' could not re-form before the goals",
      spread.s(), spread.first->id.c_str(), spread.first->arrival_s, spread.last->id.c_str(), spread.last->arrival_s,
      formation_section(sc).arrival_tolerance_s, spread.last->id.c_str());
  for (UavPlan& up : plan.uavs)
    if (up.status == Status::solved) {  // the common arrival time: a mission's rule, not a route's
      up.status = Status::failed;
      up.reason = Reason::conflict;
      up.message = buf;
    }
}

// The schedule at the formation's cruise speed, each slot's chords clear of obstacles with its
// UAV's body, the form-up's pairs kept apart.
FormationScheduleOptions schedule_options(const Scenario& sc, double cruise_mps) {
  FormationScheduleOptions so{cruise_mps, approach_m(sc, cruise_mps), {}, {}};
  so.slot_clear = [&sc](std::size_t i, const Vec3& a, const Vec3& b) {
    return sc.world.segment_valid(a, b, keep_off_m(sc.uavs[i]));
  };
  so.pair_need_m = [&sc](std::size_t i, std::size_t j) {
    constexpr double kRoom_m = 0.5;  // the flight follows the schedule in steps: room beyond the need
    return required_separation_m(sc, sc.uavs[i], sc.uavs[j]) + kRoom_m;
  };
  return so;
}

}  // namespace

void FormationMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const LocalLayer layer = local_layer(ctx);
  std::vector<Vec3> starts, goals;
  double cruise = World::kInf, vmax = World::kInf, vmin = 0.0;
  for (const UavSpec& u : sc.uavs) {
    if (!u.goal) throw std::invalid_argument("a formation UAV needs a goal ('" + u.id + "' has none)");
    starts.push_back(u.start);
    goals.push_back(*u.goal);
    cruise = std::min(cruise, u.speed.cruise_mps);
    vmax = std::min(vmax, u.speed.max_mps);
    vmin = std::max(vmin, u.speed.min_mps);
  }
  if (formation_shape(sc).size() != sc.uavs.size())
    throw std::invalid_argument("a formation mission needs one slot per UAV");
  const PlanResult ref = reference_route(sc, ctx, centroid(starts), centroid(goals));
  if (ref.status != Status::solved) return fail_all(sc, "the formation's reference route: " + ref.message, plan);
  const FormationSchedule sched =
      formation_schedule(ref.route.waypoints, formation_shape(sc), starts, goals, schedule_options(sc, cruise));

  RollingWindowOptions rw;
  rw.step_s = sc.mission.step_s;
  rw.separation_m = sc.mission.separation_m;
  rw.local = layer.rrt;
  rw.seed = ctx.options.seed;
  rw.stop = ctx.options.stop;
  std::vector<std::string> ids;
  for (const UavSpec& u : sc.uavs) ids.push_back(u.id);
  RollingWindow guard(sc.world, rw, windows_of(sc, layer), ids);
  FormationFlightOptions fo{sc.mission.step_s, sc.mission.separation_m, formation_section(sc).reform_after_steps, vmax,
                            cruise};
  fo.slow_pace = std::clamp(vmin / cruise, fo.slow_pace, 1.0);
  FormationFlight flight(sched, fo, guard);
  std::vector<LoopUav> loop;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i)
    loop.push_back({&sc.uavs[i],
                    {starts[i], sched.slots[i][1]},
                    sc.uavs[i].sensor_range_m.value_or(std::numeric_limits<double>::infinity()),
                    0.0});
  LoopOptions lo;
  lo.step_s = sc.mission.step_s;
  lo.horizon_s = 120.0 + 3.0 * sched.end_s();
  lo.max_sample_dt_s = ctx.options.max_sample_dt_s;
  lo.separation_m = sc.mission.separation_m;
  const LoopResult flown = fly_closed_loop(sc.world, loop, {}, flight, lo, ctx.options.stop);

  double eta = 0.0;
  const std::vector<Arrival> arrivals = arrival_points(sc);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const FlightState& f = flown.uavs[i];
    const RollingWindowLog& log = guard.log(i);
    // Done at the horizon while some UAV is still out of its slot: waiting, not arrived.
    const bool arrived = f.done && !flight.waiting();
    UavPlan up = flown_plan(sc.uavs[i].id, arrived, "", trajectory_corners(f.flown), f.flown);
    up.arrival_s = arrival_s(sc.uavs[i], arrivals[i], f.flown);
    up.stats = i == 0 ? ref.stats : PlanStats{};
    up.stats.plan_ms += log.local_ms;
    const std::string buf = strf("in formation (T = %g s): %d local replans, %d holds, %d escapes", sc.mission.step_s,
                                 log.replans, log.holds, log.escapes);
    const std::string by = " by t=" + std::to_string(static_cast<int>(lo.horizon_s)) + " s";
    up.message = arrived  ? std::string(buf)
                 : f.done ? "waited for the formation to re-form" + by
                          : "did not reach its goal" + by + (log.trouble.empty() ? "" : ": " + log.trouble);
    if (arrived && std::isfinite(up.arrival_s)) eta = std::max(eta, up.arrival_s);
    plan.uavs.push_back(std::move(up));
  }
  const ArrivalSpread spread = arrival_spread(plan);
  check_flown(sc, spread, plan);
  FormationLog out;
  out.eta_s = eta;
  out.arrival_spread_s = spread.s();
  out.worst_slot_error_m = flight.worst_slot_error_m();
  out.phases = {{"form_up", std::max(0.0, flight.formed_s())}, {"formation", eta}};
  for (const FormationBreak& b : flight.breaks())
    out.breaks.push_back({sc.uavs[b.uav].id, b.from_s, b.to_s >= 0.0 ? b.to_s : eta});
  plan.formation = std::move(out);
}

}  // namespace uavplan
