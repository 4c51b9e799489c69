#include "uavplan/world/shapes.h"

#include <algorithm>
#include <cmath>

#include "uavplan/core/geometry.h"

namespace uavplan {
namespace {

struct BoundsVisitor {
  Aabb operator()(const Sphere& s) const { return {s.center.array() - s.radius_m, s.center.array() + s.radius_m}; }
  Aabb operator()(const Cylinder& c) const {
    return {Vec3(c.center.x() - c.radius_m, c.center.y() - c.radius_m, c.z_min_m),
            Vec3(c.center.x() + c.radius_m, c.center.y() + c.radius_m, c.z_max_m)};
  }
  Aabb operator()(const Box& b) const { return {b.min, b.max}; }
  Aabb operator()(const Prism& p) const {
    Aabb box;
    for (const Vec2& v : p.polygon) {
      box.extend(Vec3(v.x(), v.y(), p.z_min_m));
      box.extend(Vec3(v.x(), v.y(), p.z_max_m));
    }
    return box;
  }
};

double vertical_gap(double z, double z_min, double z_max) { return std::max({0.0, z_min - z, z - z_max}); }

// The gap between the height ranges [lo, hi] and [z_min, z_max].
double vertical_gap_range(double lo, double hi, double z_min, double z_max) {
  return std::max({0.0, z_min - hi, lo - z_max});
}

struct PointVisitor {
  const Vec3& p;
  double operator()(const Sphere& s) const { return std::max(0.0, (p - s.center).norm() - s.radius_m); }
  double operator()(const Cylinder& c) const {
    const double dr = std::max(0.0, (p.head<2>() - c.center).norm() - c.radius_m);
    return std::hypot(dr, vertical_gap(p.z(), c.z_min_m, c.z_max_m));
  }
  double operator()(const Box& b) const { return Aabb{b.min, b.max}.distance(p); }
  double operator()(const Prism& pr) const {
    const Vec2 q = p.head<2>();
    const double dv = vertical_gap(p.z(), pr.z_min_m, pr.z_max_m);
    if (point_in_polygon(q, pr.polygon)) return dv;
    return std::hypot(point_polygon_boundary_distance(q, pr.polygon), dv);
  }
};

// True when the segment meets the prism's solid.
bool segment_meets_prism(const Prism& pr, const Vec3& a, const Vec3& b) {
  double t0 = 0.0, t1 = 1.0;
  const double dz = b.z() - a.z();
  if (std::abs(dz) < 1e-300) {
    if (a.z() < pr.z_min_m || a.z() > pr.z_max_m) return false;
  } else {
    double ta = (pr.z_min_m - a.z()) / dz, tb = (pr.z_max_m - a.z()) / dz;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  const Vec2 p = (a + t0 * (b - a)).head<2>(), q = (a + t1 * (b - a)).head<2>();
  if (point_in_polygon(p, pr.polygon) || point_in_polygon(q, pr.polygon)) return true;
  const std::size_t n = pr.polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++)
    if (segments_intersect_2d(p, q, pr.polygon[j], pr.polygon[i])) return true;
  return false;
}

// Where the segment's plan view lies within the cylinder's disc: [t0, t1] on [0, 1], or empty.
bool disc_interval(const Cylinder& c, const Vec3& a, const Vec3& b, double& t0, double& t1) {
  const Vec2 d = (b - a).head<2>(), f = a.head<2>() - c.center;
  const double qa = d.squaredNorm(), qb = 2.0 * f.dot(d), qc = f.squaredNorm() - c.radius_m * c.radius_m;
  if (qa < 1e-300) {
    t0 = 0.0, t1 = 1.0;
    return qc <= 0.0;
  }
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) return false;
  const double s = std::sqrt(disc);
  t0 = std::max(0.0, (-qb - s) / (2.0 * qa));
  t1 = std::min(1.0, (-qb + s) / (2.0 * qa));
  return t0 <= t1;
}

struct SegmentVisitor {
  const Vec3& a;
  const Vec3& b;
  double cap;
  double operator()(const Sphere& s) const {
    return std::max(0.0, point_segment_distance(s.center, a, b) - s.radius_m);
  }
  // Distance to a convex solid is convex along a line: golden-section search is exact. Before
  // it, two cheap answers: the plan-view and height gaps bound the distance from below, and a
  // segment whose plan view crosses the disc at a height within the cylinder meets it.
  double operator()(const Cylinder& c) const {
    const double dz = vertical_gap_range(std::min(a.z(), b.z()), std::max(a.z(), b.z()), c.z_min_m, c.z_max_m);
    const Vec3 a2(a.x(), a.y(), 0.0), b2(b.x(), b.y(), 0.0), c2(c.center.x(), c.center.y(), 0.0);
    const double dr = std::max(0.0, point_segment_distance(c2, a2, b2) - c.radius_m);
    if (std::max(dz, dr) >= cap) return std::max(dz, dr);
    double t0 = 0.0, t1 = 0.0;
    if (dr <= 0.0 && disc_interval(c, a, b, t0, t1)) {
      const double z0 = a.z() + t0 * (b.z() - a.z()), z1 = a.z() + t1 * (b.z() - a.z());
      if (std::max(z0, z1) >= c.z_min_m && std::min(z0, z1) <= c.z_max_m) return 0.0;
    }
    return golden_section_min([&](double t) { return PointVisitor{a + t * (b - a)}(c); }, 0.0, 1.0);
  }
  double operator()(const Box& bx) const {
    const Aabb box{bx.min, bx.max};
    const double gap = box.distance(Aabb{a.cwiseMin(b), a.cwiseMax(b)});  // a lower bound
    if (gap >= cap) return gap;
    double t0 = 0.0, t1 = 0.0;
    if (clip_segment_to_box(a, b, box, t0, t1)) return 0.0;
    return golden_section_min([&](double t) { return box.distance(a + t * (b - a)); }, 0.0, 1.0);
  }
  // A possibly non-convex prism: 0 when they meet; otherwise the closest pair involves an
  // endpoint of the segment or an edge of the prism.
  double operator()(const Prism& pr) const {
    if (segment_meets_prism(pr, a, b)) return 0.0;
    double best = std::min(PointVisitor{a}(pr), PointVisitor{b}(pr));
    const std::size_t n = pr.polygon.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Vec3 lo_j(pr.polygon[j].x(), pr.polygon[j].y(), pr.z_min_m);
      const Vec3 lo_i(pr.polygon[i].x(), pr.polygon[i].y(), pr.z_min_m);
      const Vec3 hi_j(lo_j.x(), lo_j.y(), pr.z_max_m), hi_i(lo_i.x(), lo_i.y(), pr.z_max_m);
      best = std::min({best, segment_segment_distance(a, b, lo_j, lo_i), segment_segment_distance(a, b, hi_j, hi_i),
                       segment_segment_distance(a, b, lo_i, hi_i)});
    }
    return best;
  }
};

struct ClosestVisitor {
  const Vec3& p;
  Vec3 operator()(const Sphere& s) const {
    const Vec3 d = p - s.center;
    const double n = d.norm();
    return n <= s.radius_m ? p : Vec3(s.center + s.radius_m / n * d);
  }
  Vec3 operator()(const Cylinder& c) const {
    Vec2 q = p.head<2>();
    const Vec2 d = q - c.center;
    if (d.norm() > c.radius_m) q = c.center + c.radius_m / d.norm() * d;
    return {q.x(), q.y(), std::clamp(p.z(), c.z_min_m, c.z_max_m)};
  }
  Vec3 operator()(const Box& b) const { return p.cwiseMax(b.min).cwiseMin(b.max); }
  Vec3 operator()(const Prism& pr) const {
    const double z = std::clamp(p.z(), pr.z_min_m, pr.z_max_m);
    const Vec2 q = p.head<2>();
    if (point_in_polygon(q, pr.polygon)) return {q.x(), q.y(), z};
    Vec2 best = pr.polygon[0];
    double best_d = 1e300;
    const std::size_t n = pr.polygon.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Vec2 ab = pr.polygon[i] - pr.polygon[j];
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((q - pr.polygon[j]).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const Vec2 c = pr.polygon[j] + t * ab;
      if ((c - q).norm() < best_d) {
        best_d = (c - q).norm();
        best = c;
      }
    }
    return {best.x(), best.y(), z};
  }
};

}  // namespace

Vec3 closest_point(const Obstacle& o, const Vec3& p) { return std::visit(ClosestVisitor{p}, o); }

Aabb bounding_box(const Obstacle& o) { return std::visit(BoundsVisitor{}, o); }

double point_distance(const Obstacle& o, const Vec3& p) { return std::visit(PointVisitor{p}, o); }

std::string_view shape_name(const Obstacle& o) {
  static constexpr std::string_view kNames[] = {"sphere", "cylinder", "box", "prism"};
  return kNames[o.index()];
}

double segment_distance(const Obstacle& o, const Vec3& a, const Vec3& b, double cap) {
  return std::visit(SegmentVisitor{a, b, cap}, o);
}

}  // namespace uavplan
