#include "uavplan/coordination/group/group_mission.h"
#include "uavplan/core/text.h"

#include <cstdio>

#include "uavplan/coordination/group/group_planner.h"
#include "uavplan/coordination/timing.h"

namespace uavplan {
namespace {

std::string limits_broken(const std::vector<Vec3>& path, const UavSpec& u) {
  const auto broken = check_route_limits(path, u);
  if (broken.empty()) return {};
  const LimitViolation& v = broken.front();
  const Vec3& p = path[v.index];
  const bool turn = v.kind == LimitViolation::Kind::turn;
  const std::string where = strf(" at (%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return std::string(turn ? "the field's path turns " : "the field's path climbs ") +
         std::to_string(rad_to_deg(v.value_rad)) + " deg" + where + ", above the limit " +
         std::to_string(rad_to_deg(turn ? u.max_turn_rad : u.max_climb_rad)) +
         " deg (an independent mission shapes each field path to the limits; or allow a larger max_turn_deg)";
}

}  // namespace

void GroupMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const GroupResult g = plan_group(
      sc, ApfOptions::from_params(ctx.params, ctx.algorithm == "apf" ? ApfField::improved : ApfField::traditional),
      ctx.options.stop);
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    GroupUav r = g.uavs[i];
    // The field steers frame by frame under the climb limit only: a path that turns beyond the
    // UAV's limit (around a goal under it, say) is not claimed.
    if (r.reached)
      if (const std::string why = limits_broken(r.smoothed, sc.uavs[i]); !why.empty()) {
        r.reached = false;
        r.message = why;
      }
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
