#include "uavplan/simulation/closed_loop.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "uavplan/core/geometry.h"

namespace uavplan {

void advance(FlightState& s, double t, double dt) {
  if (!s.flown.empty() && s.flown.back().t_s < t) s.flown.push_back({t, s.position});
  const SpeedLimits& lim = s.spec->speed;
  const double v = std::clamp(s.speed_mps, lim.min_mps, lim.max_mps);
  const double end = t + dt;
  if (v <= 0.0) {
    s.flown.push_back({end, s.position});  // hovering
    return;
  }
  double remaining = v * dt;
  // A vertex within rounding of the period's end is reached at the end: no sliver rows.
  const double eps = 1e-9 * std::max(1.0, remaining);
  std::size_t reached = 0;
  while (reached < s.route.size() && remaining > eps) {
    const Vec3 seg = s.route[reached] - s.position;
    const double len = seg.norm();
    if (len <= eps) {  // a vertex where it already is: reached, without a sliver row
      ++reached;
      continue;
    }
    if (len > remaining + eps) {
      s.position += seg / len * remaining;
      s.direction = seg / len;
      s.moved = true;
      s.flown.push_back({end, s.position});
      remaining = 0.0;
      break;
    }
    t = len >= remaining - eps ? end : t + len / v;
    remaining = t == end ? 0.0 : remaining - len;
    s.position = s.route[reached++];
    if (len > 0.0) {
      s.direction = seg / len;
      s.moved = true;
    }
    if (s.flown.empty() || s.flown.back().p != s.position || s.flown.back().t_s < t) s.flown.push_back({t, s.position});
  }
  s.route.erase(s.route.begin(), s.route.begin() + static_cast<std::ptrdiff_t>(reached));
  s.done = s.route.empty();
}

Trajectory densified(const Trajectory& tr, double max_dt) {
  Trajectory out;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    if (i > 0 && max_dt > 0.0) {
      const TrajectorySample &a = tr[i - 1], &b = tr[i];
      const int pieces = static_cast<int>(std::ceil((b.t_s - a.t_s) / max_dt - kWholeNumberSlack));
      for (int k = 1; k < pieces; ++k) {
        const double f = static_cast<double>(k) / pieces;
        out.push_back({a.t_s + f * (b.t_s - a.t_s), a.p + f * (b.p - a.p)});
      }
    }
    out.push_back(tr[i]);
  }
  return out;
}

namespace {

// Will anything that moves come within touching distance of a UAV staying at p from t on?
bool threatened(const World& world, std::span<const ScriptedUav> scripted, const UavSpec& u, const Vec3& p, double t,
                double separation_m) {
  if (closest_moving_approach(world, Trajectory{{t, p}}).distance_m < u.radius_m) return true;
  for (const ScriptedUav& o : scripted) {
    const Trajectory& tr = *o.trajectory;
    const double need = std::max(separation_m, u.radius_m + o.spec->radius_m);
    Vec3 a = position_at(tr, t);
    if ((a - p).norm() < need) return true;
    for (const TrajectorySample& row : tr) {
      if (row.t_s <= t) continue;
      if (point_segment_distance(p, a, row.p) < need) return true;
      a = row.p;
    }
  }
  return false;
}

}  // namespace

LoopResult fly_closed_loop(const World& world, std::span<const LoopUav> uavs, std::span<const ScriptedUav> scripted,
                           FlightController& controller, const LoopOptions& opt, const StopCondition& stop) {
  LoopResult res;
  const std::size_t n_moving = world.moving().size(), first_uav = n_moving + scripted.size();
  std::vector<ObjectState> truth(first_uav + uavs.size());
  for (std::size_t k = 0; k < n_moving; ++k) truth[k] = {world.moving()[k].id, world.moving()[k].radius_m, false, {}};
  for (std::size_t k = 0; k < scripted.size(); ++k)
    truth[n_moving + k] = {scripted[k].spec->id, scripted[k].spec->radius_m, true, {}};
  std::vector<Sensor> sensors(uavs.size());
  for (const LoopUav& u : uavs) {
    FlightState s;
    s.spec = u.spec;
    s.position = u.route.empty() ? u.spec->start : u.route.front();
    s.route.assign(u.route.begin() + (u.route.empty() ? 0 : 1), u.route.end());
    s.speed_mps = u.spec->speed.cruise_mps;
    s.depart_s = u.depart_s;
    if (u.spec->heading_rad)
      s.direction = heading_vector(*u.spec->heading_rad);
    else if (!s.route.empty() && s.route.front() != s.position)
      s.direction = (s.route.front() - s.position).normalized();
    s.flown.push_back({0.0, s.position});
    s.done = s.route.empty();
    sensors[res.uavs.size()].range_m = u.sensor_range_m;
    truth[first_uav + res.uavs.size()] = {u.spec->id, u.spec->radius_m, true, s.position};
    res.uavs.push_back(std::move(s));
  }
  const auto finished = [&](double t) {
    if (controller.waiting()) return false;
    for (const FlightState& s : res.uavs)
      if (!s.done || threatened(world, scripted, *s.spec, s.position, t, opt.separation_m)) return false;
    return true;
  };
  for (int k = 0;; ++k) {
    const double t = k * opt.step_s;
    if (finished(t)) break;
    if (t >= opt.horizon_s || stop.should_stop()) {
      res.stopped = true;
      break;
    }
    for (std::size_t m = 0; m < n_moving; ++m) truth[m].position = world.moving()[m].position_at(t);
    for (std::size_t m = 0; m < scripted.size(); ++m)
      truth[n_moving + m].position = position_at(*scripted[m].trajectory, t);
    for (std::size_t i = 0; i < uavs.size(); ++i) truth[first_uav + i].position = res.uavs[i].position;
    for (std::size_t i = 0; i < uavs.size(); ++i) sense(sensors[i], truth, first_uav + i, res.uavs[i].position, t);
    controller.control(t, res.uavs, sensors);
    for (FlightState& s : res.uavs)
      if (!s.route.empty() && t + kSameTime_s >= s.depart_s) advance(s, t, opt.step_s);
    res.steps = k + 1;
  }
  for (FlightState& s : res.uavs) s.flown = densified(s.flown, opt.max_sample_dt_s);
  return res;
}

}  // namespace uavplan
