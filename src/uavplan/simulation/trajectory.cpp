#include "uavplan/simulation/trajectory.h"

#include <algorithm>
#include <cmath>

#include "uavplan/core/geometry.h"

namespace uavplan {

Trajectory time_route(std::span<const Vec3> pts, double speed_mps, double depart_s, double max_dt_s) {
  Trajectory tr;
  if (pts.empty()) return tr;
  tr.push_back({0.0, pts[0]});
  double t = std::max(0.0, depart_s);
  if (t > 0.0) tr.push_back({t, pts[0]});
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double len = (pts[i] - pts[i - 1]).norm();
    if (len <= 0.0) continue;
    const double dur = len / speed_mps;
    const int pieces = max_dt_s > 0.0 ? std::max(1, static_cast<int>(std::ceil(dur / max_dt_s - 1e-9))) : 1;
    for (int k = 1; k <= pieces; ++k) {
      const double f = static_cast<double>(k) / pieces;
      tr.push_back({t + f * dur, k == pieces ? pts[i] : Vec3(pts[i - 1] + f * (pts[i] - pts[i - 1]))});
    }
    t += dur;
  }
  return tr;
}

Vec3 position_at(const Trajectory& tr, double t) {
  if (tr.empty()) return Vec3::Zero();
  if (t <= tr.front().t_s) return tr.front().p;
  if (t >= tr.back().t_s) return tr.back().p;
  const auto it = std::upper_bound(tr.begin(), tr.end(), t,
                                   [](double x, const TrajectorySample& s) { return x < s.t_s; });
  const TrajectorySample& b = *it;
  const TrajectorySample& a = *(it - 1);
  const double span = b.t_s - a.t_s;
  if (span <= 0.0) return b.p;
  return a.p + (t - a.t_s) / span * (b.p - a.p);
}

Encounter closest_approach(const Trajectory& a, const Trajectory& b, double t_max_s) {
  Encounter e;
  if (a.empty() || b.empty()) return e;
  std::vector<double> times;
  times.reserve(a.size() + b.size());
  for (const auto& s : a) times.push_back(s.t_s);
  for (const auto& s : b) times.push_back(s.t_s);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  if (t_max_s < times.back()) {
    times.erase(std::upper_bound(times.begin(), times.end(), t_max_s), times.end());
    times.push_back(t_max_s);
  }
  auto consider = [&](double t0, double t1) {
    const Vec3 pa0 = position_at(a, t0), pa1 = position_at(a, t1);
    const Vec3 d0 = pa0 - position_at(b, t0), d1 = pa1 - position_at(b, t1);
    double u = 0.0;
    const double dist = point_segment_distance(Vec3::Zero(), d0, d1, &u);
    if (dist < e.distance_m) {
      e.distance_m = dist;
      e.t_s = t0 + u * (t1 - t0);
      e.where = pa0 + u * (pa1 - pa0);
    }
  };
  consider(times.front(), times.front());
  for (std::size_t i = 1; i < times.size(); ++i) consider(times[i - 1], times[i]);
  return e;
}

Encounter closest_moving_approach(const World& world, const Trajectory& tr, int* index_out) {
  Encounter e;
  if (world.moving().empty() || tr.empty()) return e;
  auto consider = [&](const TrajectorySample& s0, const TrajectorySample& s1) {
    int idx = -1;
    const double gap = world.moving_clearance(s0.p, s0.t_s, s1.p, s1.t_s, &idx);
    if (gap < e.distance_m) {
      e.distance_m = gap;
      e.t_s = s0.t_s;
      e.where = s0.p;
      if (index_out) *index_out = idx;
    }
  };
  consider(tr.front(), tr.front());
  for (std::size_t i = 1; i < tr.size(); ++i) consider(tr[i - 1], tr[i]);
  // After arrival the UAV stays at its last position while obstacles keep moving: check until
  // every obstacle has passed (its closest approach to the point), or an hour on.
  const TrajectorySample& last = tr.back();
  double t_far = last.t_s;
  for (const auto& m : world.moving()) {
    const double v2 = m.velocity_mps.squaredNorm();
    if (v2 > 0.0) t_far = std::max(t_far, (last.p - m.position).dot(m.velocity_mps) / v2);
  }
  if (t_far > last.t_s) consider(last, {t_far, last.p});
  return e;
}

}  // namespace uavplan
