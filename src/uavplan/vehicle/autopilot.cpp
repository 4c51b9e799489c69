#include "uavplan/vehicle/autopilot.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <cmath>
#include <stdexcept>

namespace uavplan {
namespace {

using State = std::array<double, 6>;  // x, y, z, z', v, phi

double wrap_pi(double a) { return std::remainder(a, 2.0 * kPi); }

State pack(const AutopilotState& s) {
  return {s.position.x(), s.position.y(), s.position.z(), s.climb_rate_mps, s.speed_mps, s.heading_rad};
}

AutopilotState unpack(const State& x) { return {Vec3(x[0], x[1], x[2]), x[3], x[4], wrap_pi(x[5])}; }

}  // namespace

AutopilotModel::AutopilotModel(AutopilotParams params, AutopilotLimits limits, double step_s)
    : p_(params), lim_(limits), step_s_(step_s) {
  for (const double tau : {p_.tau_v_s, p_.tau_heading_s, p_.tau_zdot_s, p_.tau_z_s})
    if (!(tau > 0.0)) throw std::invalid_argument("autopilot time constants must be > 0");
  if (!(step_s_ > 0.0)) throw std::invalid_argument("autopilot integration step must be > 0");
  if (!(lim_.max_turn_rate_rad_s > 0.0) || !(lim_.max_climb_rate_mps > 0.0))
    throw std::invalid_argument("autopilot turn and climb rate limits must be > 0");
}

void AutopilotModel::advance(AutopilotState& state, const AutopilotCommand& c, double dt_s) const {
  const double v_c = std::clamp(c.speed_mps, lim_.speed.min_mps, lim_.speed.max_mps);
  const double climb = lim_.max_climb_rate_mps, turn = lim_.max_turn_rate_rad_s;
  // Eq. 1 with the saturations: the turn rate clipped, the climb rate held at its limit.
  const auto rhs = [&](const State& x, State& dx, double) {
    dx[0] = x[4] * std::cos(x[5]);
    dx[1] = x[4] * std::sin(x[5]);
    dx[2] = x[3];
    double zdd = std::clamp(-x[3] / p_.tau_zdot_s + (c.altitude_m - x[2]) / p_.tau_z_s, -lim_.max_vertical_accel_mps2,
                            lim_.max_vertical_accel_mps2);
    if ((x[3] >= climb && zdd > 0.0) || (x[3] <= -climb && zdd < 0.0)) zdd = 0.0;
    dx[3] = zdd;
    dx[4] = (v_c - x[4]) / p_.tau_v_s;
    dx[5] = std::clamp(wrap_pi(c.heading_rad - x[5]) / p_.tau_heading_s, -turn, turn);
  };
  boost::numeric::odeint::runge_kutta4<State> rk4;
  State x = pack(state);
  const int steps = std::max(1, static_cast<int>(std::ceil(dt_s / step_s_ - kWholeNumberSlack)));
  const double h = dt_s / steps;
  for (int k = 0; k < steps; ++k) {
    rk4.do_step(rhs, x, k * h, h);
    x[3] = std::clamp(x[3], -climb, climb);
  }
  state = unpack(x);
}

double switch_radius_m(const AutopilotModel& model, double cruise_mps, double turn_rad, const FollowOptions& o) {
  if (o.switch_radius_m > 0.0) return o.switch_radius_m;
  const double lag = 2.0 * cruise_mps * model.params().tau_heading_s;
  if (!std::isfinite(model.limits().max_turn_rate_rad_s)) return lag;
  // The turn's tangent point: an arc of the turn radius R through the corner starts R tan(turn / 2)
  // before it.
  const double radius = cruise_mps / model.limits().max_turn_rate_rad_s;
  return std::max(lag, radius * std::tan(0.5 * std::min(std::abs(turn_rad), 0.5 * kPi)));
}

FollowResult follow_waypoints(const AutopilotModel& model, AutopilotState s, const std::vector<Vec3>& waypoints,
                              double cruise_mps, const FollowOptions& o) {
  FollowResult r;
  r.samples.push_back({0.0, s});
  if (waypoints.empty()) {
    r.reached = true;
    return r;
  }
  const double h = model.step_s();
  // The last waypoint is caught within a heading time constant's flight (its remainder is flown
  // straight onto it by the caller); missed, the heading hold brings the UAV round again.
  const double capture = std::max(2.0 * cruise_mps * h, cruise_mps * model.params().tau_heading_s);
  Vec3 from = s.position;
  std::size_t k = 0;
  double t = 0.0, next_sample = o.sample_s;
  while (t < o.max_time_s) {
    const Vec3& to = waypoints[k];
    const bool last = k + 1 == waypoints.size();
    const Vec3 rel = s.position - to;
    double radius = 0.0;
    if (!last) {
      const Vec3 in = to - from, out = waypoints[k + 1] - to;
      const double turn = in.head<2>().norm() > 0.0 && out.head<2>().norm() > 0.0
                              ? std::remainder(std::atan2(out.y(), out.x()) - std::atan2(in.y(), in.x()), 2.0 * kPi)
                              : 0.0;
      radius = switch_radius_m(model, cruise_mps, turn, o);
    }
    const double d = rel.norm();
    if (last) r.closest_to_goal_m = std::min(r.closest_to_goal_m, d);
    // Passed: close enough, or beyond it along the leg into it (horizontally).
    const Vec3 leg = to - from;
    const bool beyond = leg.head<2>().squaredNorm() > 0.0 && rel.head<2>().dot(leg.head<2>()) > 0.0;
    const bool over = k < o.fly_over.size() && o.fly_over[k];
    if (!last && over && d <= 2.0 * cruise_mps * h) {  // flown over: on to the closest approach, a row there
      const Vec3 vel(s.speed_mps * std::cos(s.heading_rad), s.speed_mps * std::sin(s.heading_rad), s.climb_rate_mps);
      const double dt =
          vel.squaredNorm() > 0.0 ? std::clamp((to - s.position).dot(vel) / vel.squaredNorm(), 0.0, 2.0 * h) : 0.0;
      if (dt > 0.0) {
        const Vec3 aim = to - s.position;
        model.advance(s, {cruise_mps, to.z(), std::atan2(aim.y(), aim.x())}, dt);
        t += dt;
      }
      r.samples.push_back({t, s});
      next_sample = t + o.sample_s;
      from = to;
      ++k;
      continue;
    }
    if ((!last && !over && (d <= radius || beyond)) || (last && d <= capture)) {
      if (last) {
        r.reached = true;
        break;
      }
      from = to;
      ++k;
      continue;
    }
    const Vec3 aim = to - s.position;
    const double bearing = aim.head<2>().norm() > kSamePoint_m ? std::atan2(aim.y(), aim.x()) : s.heading_rad;
    model.advance(s, {cruise_mps, to.z(), bearing}, h);
    t += h;
    if (t + kSameTime_s >= next_sample) {
      r.samples.push_back({t, s});
      next_sample += o.sample_s;
    }
  }
  if (r.samples.back().t_s < t) r.samples.push_back({t, s});
  return r;
}

}  // namespace uavplan
