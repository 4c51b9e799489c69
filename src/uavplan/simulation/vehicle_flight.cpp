#include "uavplan/simulation/vehicle_flight.h"
#include "uavplan/core/geometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace uavplan {

AutopilotModel autopilot_of(const UavSpec& u) {
  AutopilotLimits lim;
  lim.speed = u.speed;
  if (u.max_turn_rate_rad_s) lim.max_turn_rate_rad_s = *u.max_turn_rate_rad_s;
  if (u.max_climb_rate_mps) lim.max_climb_rate_mps = *u.max_climb_rate_mps;
  return AutopilotModel(u.model.value_or(AutopilotParams{}), lim);
}

Trajectory fly_route(const UavSpec& u, std::span<const Vec3> waypoints, double depart_s, double max_dt_s,
                     std::span<const Vec3> fly_over) {
  if (!u.model || waypoints.size() < 2) return time_route(waypoints, u.speed.cruise_mps, depart_s, max_dt_s);
  const AutopilotModel model = autopilot_of(u);
  AutopilotState s;
  s.position = waypoints.front();
  s.speed_mps = u.speed.cruise_mps;
  const Vec3 first = waypoints[1] - waypoints[0];
  s.heading_rad = u.heading_rad ? *u.heading_rad : std::atan2(first.y(), first.x());
  const double route_m = polyline_length_m(waypoints);
  FollowOptions fo;
  fo.sample_s = max_dt_s > 0.0 ? std::min(max_dt_s, 1.0) : 1.0;
  fo.max_time_s = 3.0 * route_m / u.speed.cruise_mps + 600.0;
  const std::vector<Vec3> rest(waypoints.begin() + 1, waypoints.end());
  for (const Vec3& w : rest) fo.fly_over.push_back(std::find(fly_over.begin(), fly_over.end(), w) != fly_over.end());
  const FollowResult r = follow_waypoints(model, s, rest, u.speed.cruise_mps, fo);
  if (!r.reached) return {};
  Trajectory tr;
  const double t0 = std::max(0.0, depart_s);
  tr.push_back({0.0, waypoints.front()});
  for (const FollowSample& f : r.samples)
    if (t0 + f.t_s > tr.back().t_s) tr.push_back({t0 + f.t_s, f.state.position});
  // Onto the last waypoint, the few metres left, at the speed flown.
  const FollowSample& end = r.samples.back();
  const double gap = (waypoints.back() - end.state.position).norm();
  if (gap > 0.0) tr.push_back({tr.back().t_s + gap / std::max(end.state.speed_mps, 1e-6), waypoints.back()});
  return tr;
}

}  // namespace uavplan
