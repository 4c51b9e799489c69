// Small geometric value types shared by every layer.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <limits>

namespace uavplan {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Axis-aligned box; an empty box has min > max.
struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  static Aabb of(const Vec3& a, const Vec3& b) { return {a.cwiseMin(b), a.cwiseMax(b)}; }
  bool empty() const { return (min.array() > max.array()).any(); }
  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  Aabb inflated(double margin) const { return {min.array() - margin, max.array() + margin}; }
  Vec3 center() const { return 0.5 * (min + max); }
  Vec3 extent() const { return max - min; }
  bool contains(const Vec3& p) const { return (p.array() >= min.array()).all() && (p.array() <= max.array()).all(); }
  bool overlaps(const Aabb& b) const {
    return (min.array() <= b.max.array()).all() && (b.min.array() <= max.array()).all();
  }
  // Euclidean distance from p to the box (0 inside).
  double distance(const Vec3& p) const {
    const Vec3 d = (min - p).cwiseMax(p - max).cwiseMax(Vec3::Zero());
    return d.norm();
  }
  // Euclidean gap between two boxes (0 when they overlap).
  double distance(const Aabb& b) const {
    const Vec3 d = (min - b.max).cwiseMax(b.min - max).cwiseMax(Vec3::Zero());
    return d.norm();
  }
};

}  // namespace uavplan
