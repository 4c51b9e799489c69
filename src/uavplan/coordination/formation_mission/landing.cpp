#include "uavplan/coordination/formation_mission/landing.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

namespace uavplan {
namespace {

double wrap_2pi(double a) {
  a = std::fmod(a, 2.0 * kPi);
  return a < 0.0 ? a + 2.0 * kPi : a;
}

}  // namespace

LandingResult plan_landing(const Airfield& af, const AutopilotModel& model, const AutopilotState& state, double t0_s,
                           const LandingOptions& o, const std::function<bool(const Trajectory&)>& conflicts) {
  LandingResult best;
  const Vec3 dir(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0);
  const Vec3& thr = af.position;
  const double ground = thr.z(), z_gate = ground + o.gate_height_m;
  const Vec3 centre = thr - o.cylinder_before_threshold_m * dir;
  const double omega =
      std::isfinite(model.limits().max_turn_rate_rad_s) ? model.limits().max_turn_rate_rad_s : deg_to_rad(3.0);
  const SpeedLimits& lim = model.limits().speed;
  // Touch-down 5 % down the runway, stopped by 45 %: within its first half whichever end
  // `position` names.
  const Vec3 touch = thr + 0.05 * af.runway_length_m * dir, stop = thr + 0.45 * af.runway_length_m * dir;
  const Vec3 gate = thr - o.gate_before_threshold_m * dir + Vec3(0, 0, o.gate_height_m);
  const double final_m = 0.4 * o.gate_before_threshold_m;
  const Vec3 final_fix = thr - final_m * dir + Vec3(0, 0, o.gate_height_m * final_m / o.gate_before_threshold_m);
  best.reason = Reason::conflict;
  best.message = "no conflict-free landing at any speed in [" + std::to_string(static_cast<int>(lim.min_mps)) + ", " +
                 std::to_string(static_cast<int>(lim.max_mps)) + "] m/s within " + std::to_string(o.max_holds) +
                 " holds";
  // The speeds tried, from the fastest down by the step, and the least speed (the circle inside
  // the cylinder may need it: fit_airfield sizes the cylinder for it).
  std::vector<double> speeds;
  for (double v = lim.max_mps; v >= lim.min_mps - 1e-9; v -= o.speed_step_mps) speeds.push_back(v);
  if (speeds.empty() || speeds.back() > lim.min_mps + 1e-9) speeds.push_back(lim.min_mps);
  for (int holds = 0; holds <= o.max_holds; ++holds) {
    for (const double v : speeds) {
      const double r_turn = v / omega;
      if (r_turn > 0.8 * o.cylinder_radius_m) continue;  // cannot circle inside the cylinder
      const double r = std::clamp(1.25 * r_turn, 0.5 * o.cylinder_radius_m, 0.85 * o.cylinder_radius_m);
      // Counter-clockwise: at angle theta the heading is theta + 90 deg; the exit is where it is
      // the runway heading.
      const Vec2 rel = (state.position - centre).head<2>();
      const double th0 = rel.norm() > 0.0 ? std::atan2(rel.y(), rel.x()) : af.runway_heading_rad;
      const double th_exit = af.runway_heading_rad - 0.5 * kPi;
      const double z0 = state.position.z();
      const double descent = std::max(0.0, (z0 - z_gate) / o.max_descent_mps * v / r);  // radians of spiral
      double total = 2.0 * kPi * holds + descent;
      total += wrap_2pi(th0 + total - th_exit) > 0.0 ? 2.0 * kPi - wrap_2pi(th0 + total - th_exit) : 0.0;
      std::vector<Vec3> wps;
      const int n = std::max(1, static_cast<int>(std::ceil(total / deg_to_rad(30.0))));
      for (int k = 0; k <= n; ++k) {
        const double a = total * k / n, th = th0 + a;
        const double down =
            std::clamp((a - 2.0 * kPi * holds) / std::max(total - 2.0 * kPi * holds, kTinyDivisor), 0.0, 1.0);
        wps.emplace_back(centre.x() + r * std::cos(th), centre.y() + r * std::sin(th), z0 + down * (z_gate - z0));
      }
      wps.push_back(gate);
      wps.push_back(final_fix);
      FollowOptions fo;
      fo.sample_s = o.sample_s;
      fo.max_time_s = 4.0 * (total * r + (state.position - centre).norm() + o.cylinder_before_threshold_m) / v + 600.0;
      const FollowResult fr = follow_waypoints(model, state, wps, v, fo);
      if (!fr.reached) continue;
      Trajectory flight;
      for (const FollowSample& s : fr.samples) flight.push_back({t0_s + s.t_s, s.state.position});
      const double to_fix = (final_fix - flight.back().p).norm();
      if (to_fix > 0.0) flight.push_back({flight.back().t_s + to_fix / v, final_fix});
      append_straight_run(flight, touch, v, v, o.sample_s);
      append_straight_run(flight, stop, v, 0.0, o.sample_s);
      if (conflicts(flight)) continue;
      best.succeed();
      best.message.clear();
      best.flight = std::move(flight);
      best.speed_mps = v;
      best.holds = holds;
      return best;
    }
  }
  return best;
}

}  // namespace uavplan
