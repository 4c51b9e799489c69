#include "uavplan/coordination/routes_mission.h"

#include "uavplan/coordination/timing.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

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
    Departure d = earliest_departure(sc, u, up.waypoints, horizon_s, committed, opt.delay_step_s, opt.max_sample_dt_s);
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

}  // namespace

void RoutesMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const auto planner = make_planner(ctx.algorithm, ctx.params);
  plan_routes(sc, *planner, ctx.options, plan);
  time_routes(sc, ctx.options, plan);
}

}  // namespace uavplan
