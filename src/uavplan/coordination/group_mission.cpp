#include "uavplan/coordination/group_mission.h"

#include "uavplan/coordination/group_planner.h"
#include "uavplan/coordination/timing.h"

namespace uavplan {

void GroupMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const GroupResult g = plan_group(sc, ApfOptions::from_params(ctx.params, ctx.algorithm == "apf"), ctx.options.stop);
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
  if (ctx.options.progress) ctx.options.progress(sc.uavs.size(), sc.uavs.size());
}

}  // namespace uavplan
