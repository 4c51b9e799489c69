// Small geometric value types shared by every layer.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
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
  // Euclidean distance from p to the box (0 inside). Written on the raw coordinates: this is the
  // innermost step of every clearance query (each BVH node), and an expression of Eigen
  // temporaries that the optimiser flattens in a release build stays a chain of calls in an
  // instrumented (sanitizer) one.
  double distance(const Vec3& p) const { return gap(min.data(), max.data(), p.data(), p.data()); }
  // Euclidean gap between two boxes (0 when they overlap).
  double distance(const Aabb& b) const { return gap(min.data(), max.data(), b.min.data(), b.max.data()); }

 private:
  // The gap between [lo, hi] and [other_lo, other_hi], axis by axis (at most one side is positive
  // on an axis of a non-empty box).
  static double gap(const double* lo, const double* hi, const double* other_lo, const double* other_hi) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double below = lo[i] - other_hi[i], above = other_lo[i] - hi[i];
      const double d = below > 0.0 ? below : above > 0.0 ? above : 0.0;
      sum += d * d;
    }
    return std::sqrt(sum);
  }
};

}  // namespace uavplan
