#include "uavplan/coordination/mission_planner.h"

#include <algorithm>
#include <chrono>

#include "uavplan/coordination/planning_view.h"
#include "uavplan/planning/registry.h"

namespace uavplan {

namespace {

// Parameters the chosen planner does not take but another registered one does are dropped with a
// note (so one file can compare planners); the mission's own ones go to it. Others stay, and the
// planner refuses them (a typo is bad input).
void sort_params(const Mission* mission, MissionContext& ctx, std::vector<std::string>& notes) {
  const std::vector<std::string> own = mission ? mission->declaration().parameters : std::vector<std::string>{};
  Params kept;
  for (const auto& [key, value] : ctx.params) {
    if (std::find(own.begin(), own.end(), key) != own.end()) {
      ctx.mission_params[key] = value;
      continue;
    }
    if (planner_accepts(ctx.algorithm, key, value)) {
      kept[key] = value;
      continue;
    }
    std::string others;
    for (const PlannerInfo& p : planner_catalog())
      if (p.name != ctx.algorithm && planner_accepts(p.name, key, value))
        others += (others.empty() ? "" : ", ") + p.name;
    if (others.empty()) {
      kept[key] = value;  // nobody's: the planner names it as unknown
      continue;
    }
    notes.push_back("planner.params." + key + " is not a parameter of " + ctx.algorithm + " (it is one of " + others +
                    "): ignored");
  }
  ctx.params = std::move(kept);
}

}  // namespace

Plan plan_mission(const Scenario& sc, const MissionOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Plan plan;
  plan.scenario = sc.name;
  plan.seed = opt.seed;
  Params params = sc.planner.params;
  for (const auto& [k, v] : opt.params) params[k] = v;
  const Mission* mission = find_mission(sc.mission.type);
  MissionContext ctx{opt, mission_algorithm(sc, opt.algorithm), params, {}, {}};
  sort_params(mission, ctx, plan.notes);
  plan.algorithm = ctx.algorithm;
  make_planner(ctx.algorithm, ctx.params);  // unknown names and parameters are errors for every mission
  const PlanningView view = planning_view(
      sc, mission && mission->declaration().times_ground_legs ? GroundLegTiming::by_mission : GroundLegTiming::shifted);
  ctx.ground = view.ground;
  if (mission) {
    try {
      mission->plan(view.identity ? sc : view.scenario, ctx, plan);
    } catch (const Stopped&) {  // a set-up outside the planners (a roadmap, a map) was stopped
      for (std::size_t i = plan.uavs.size(); i < sc.uavs.size(); ++i) {
        UavPlan& up = plan.uavs.emplace_back();
        up.id = sc.uavs[i].id;
        up.message = kStoppedMessage;
      }
      for (UavPlan& up : plan.uavs)
        if (up.status != Status::solved) up.reason = Reason::stopped;
    }
    to_scenario(view, sc, plan, opt.max_sample_dt_s);
    for (std::size_t i = 0; i < plan.uavs.size() && i < view.arrival_problem.size(); ++i)
      if (!view.arrival_problem[i].empty() && plan.uavs[i].status == Status::solved) {
        plan.uavs[i].status = Status::failed;
        plan.uavs[i].message = view.arrival_problem[i];
      }
  } else {
    for (const auto& u : sc.uavs) {
      UavPlan up;
      up.id = u.id;
      up.message = "mission type '" + sc.mission.type + "' is not supported by planner '" + plan.algorithm + "'";
      plan.uavs.push_back(std::move(up));
    }
  }
  // The distance each flew (the metrics, after verification, say the same).
  for (UavPlan& u : plan.uavs) u.length_m = flown_length_m(u.trajectory);
  // A UAV a mission failed without saying why in a word: stopped, or no route it could fly.
  for (UavPlan& u : plan.uavs)
    if (u.status != Status::solved && u.reason == Reason::none)
      u.reason = opt.stop.should_stop() ? Reason::stopped : Reason::no_route;
  combine_outcomes(plan);
  plan.plan_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return plan;
}

}  // namespace uavplan
