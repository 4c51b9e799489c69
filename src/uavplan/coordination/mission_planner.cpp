#include "uavplan/coordination/mission_planner.h"

#include <algorithm>
#include <chrono>

#include "uavplan/planning/registry.h"

namespace uavplan {

Plan plan_mission(const Scenario& sc, const MissionOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Plan plan;
  plan.scenario = sc.name;
  plan.seed = opt.seed;
  const std::string requested = opt.algorithm.value_or(sc.planner.algorithm);
  Params params = sc.planner.params;
  for (const auto& [k, v] : opt.params) params[k] = v;
  const Mission* mission = find_mission(sc.mission.type);
  MissionContext ctx{opt, requested, params, {}};
  if (mission)
    for (const std::string& key : mission->parameters())
      if (const auto it = ctx.params.find(key); it != ctx.params.end()) {
        ctx.mission_params.insert(*it);
        ctx.params.erase(it);
      }
  const std::vector<std::string> allowed = mission ? mission->algorithms() : std::vector<std::string>{};
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), requested) == allowed.end()) {
    // The mission plans with its own method: other planners' parameters do not apply.
    ctx.algorithm = allowed.front();
    ctx.params.clear();
  }
  plan.algorithm = ctx.algorithm;
  make_planner(ctx.algorithm, ctx.params);  // unknown names and parameters are errors for every mission
  if (mission) {
    mission->plan(sc, ctx, plan);
  } else {
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
