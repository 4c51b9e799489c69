#include "uavplan/world/moving.h"

#include <algorithm>

namespace uavplan {
namespace {

// The first row after t (path.end() when none).
std::vector<TimedPoint>::const_iterator after(const std::vector<TimedPoint>& path, double t) {
  return std::upper_bound(path.begin(), path.end(), t, [](double x, const TimedPoint& r) { return x < r.t_s; });
}

}  // namespace

Vec3 MovingObstacle::position_at(double t) const {
  if (path.empty()) return position + t * velocity_mps;
  if (t <= path.front().t_s) return path.front().p;
  if (t >= path.back().t_s) return path.back().p;
  const auto b = after(path, t);
  const auto a = b - 1;
  return a->p + (t - a->t_s) / (b->t_s - a->t_s) * (b->p - a->p);
}

Vec3 MovingObstacle::velocity_at(double t) const {
  if (path.empty()) return velocity_mps;
  if (t < path.front().t_s || t >= path.back().t_s) return Vec3::Zero();
  const auto b = after(path, t);
  const auto a = b - 1;
  return (b->p - a->p) / (b->t_s - a->t_s);
}

}  // namespace uavplan
