#include "uavplan/coordination/timing.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cstdio>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/simulation/vehicle_flight.h"

namespace uavplan {
namespace {

std::string at(const Encounter& e) {
  return strf("t=%.2f s at (%.1f, %.1f, %.1f)", e.t_s, e.where.x(), e.where.y(), e.where.z());
}

}  // namespace

Conflict find_conflict(const Scenario& sc, const UavSpec& uav, const Trajectory& tr, const Committed& committed,
                       MovingObstacles moving) {
  int idx = -1;
  const Encounter m = moving == MovingObstacles::avoided ? closest_moving_approach(sc.world, tr, &idx) : Encounter{};
  if (m.distance_m < uav.radius_m + kTimingMargin_m)
    return {true, "moving obstacle '" + sc.world.moving()[idx].id + "' at " + at(m)};
  for (const auto& [spec, other] : committed) {
    const Encounter e = closest_approach(tr, other->trajectory);
    if (e.distance_m < required_separation_m(sc, uav, *spec) + kTimingMargin_m)
      return {true, "UAV '" + other->id + "' at " + at(e)};
  }
  return {};
}

Departure earliest_departure(const Scenario& sc, const UavSpec& u, const std::vector<Vec3>& waypoints,
                             double max_delay_s, const Committed& committed, double delay_step_s,
                             double max_sample_dt_s, const StopCondition& stop, MovingObstacles moving) {
  Departure d;
  for (int k = 0; k == 0 || (delay_step_s > 0.0 && k * delay_step_s <= max_delay_s + kSameTime_s); ++k) {
    if (stop.should_stop()) {
      d.stopped = true;
      break;
    }
    const double delay = k * delay_step_s;
    Trajectory tr = fly_route(u, waypoints, delay, max_sample_dt_s, sc.mission.waypoints);
    if (tr.empty()) break;  // its model cannot fly the route at all
    const Conflict c = find_conflict(sc, u, tr, committed, moving);
    if (!d.first.any) d.first = c;
    if (c.any) continue;
    d.placed = true;
    d.delay_s = delay;
    d.trajectory = std::move(tr);
    break;
  }
  return d;
}

void fail_all(const Scenario& sc, const std::string& why, Plan& plan) {
  for (const UavSpec& u : sc.uavs) plan.uavs.push_back(flown_plan(u.id, false, why, {}, {}));
}

UavPlan flown_plan(const std::string& id, bool ok, std::string message, std::vector<Vec3> waypoints,
                   Trajectory trajectory) {
  UavPlan up;
  up.id = id;
  up.status = ok ? Status::solved : Status::failed;
  up.message = std::move(message);
  if (ok) {
    up.waypoints = std::move(waypoints);
    up.waypoints.erase(std::unique(up.waypoints.begin(), up.waypoints.end()), up.waypoints.end());
    up.route_length_m = Route{up.waypoints}.length_m();
    up.trajectory = std::move(trajectory);
    up.arrival_s = up.trajectory.back().t_s;
  }
  return up;
}

}  // namespace uavplan
