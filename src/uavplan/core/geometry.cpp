#include "uavplan/core/geometry.h"

#include <algorithm>
#include <cmath>

#include <boost/geometry/algorithms/correct.hpp>
#include <boost/geometry/algorithms/difference.hpp>
#include <boost/geometry/algorithms/intersects.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/geometries/ring.hpp>

namespace uavplan {

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double* t_out) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  if (t_out) *t_out = t;
  return (a + t * ab - p).norm();
}

double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kEps = 1e-18;
  double s = 0.0, t = 0.0;
  if (a <= kEps && e <= kEps) return r.norm();
  if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > kEps * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p0 + s * d1 - (q0 + t * d2)).norm();
}

bool clip_segment_to_box(const Vec3& a, const Vec3& b, const Aabb& box, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const Vec3 d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-300) {
      if (a[k] < box.min[k] || a[k] > box.max[k]) return false;
      continue;
    }
    double ta = (box.min[k] - a[k]) / d[k], tb = (box.max[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

bool point_in_polygon(const Vec2& p, std::span<const Vec2> poly) {
  bool inside = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double point_polygon_boundary_distance(const Vec2& p, std::span<const Vec2> poly) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 ab = poly[i] - poly[j];
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - poly[j]).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (poly[j] + t * ab - p).norm());
  }
  return best;
}

namespace {
double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}
}  // namespace

bool segments_intersect_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross2(c, d, a), d2 = cross2(c, d, b), d3 = cross2(a, b, c), d4 = cross2(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  if (d1 == 0 && on_segment(c, d, a)) return true;
  if (d2 == 0 && on_segment(c, d, b)) return true;
  if (d3 == 0 && on_segment(a, b, c)) return true;
  if (d4 == 0 && on_segment(a, b, d)) return true;
  return false;
}

std::optional<std::pair<std::size_t, std::size_t>> polygon_self_intersection(std::span<const Vec2> poly) {
  namespace bg = boost::geometry;
  using Point = bg::model::d2::point_xy<double>;
  bg::model::ring<Point, true, false> ring;  // either orientation; open (the last vertex joins the first)
  for (const Vec2& v : poly) ring.push_back(Point(v.x(), v.y()));
  if (!bg::intersects(ring)) return std::nullopt;
  const std::size_t n = poly.size();
  if (n > kLocatedPolygonVertices) return std::make_pair(std::size_t{0}, std::size_t{0});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing vertex
      if (segments_intersect_2d(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) return std::make_pair(i, j);
    }
  return std::make_pair(std::size_t{0}, std::size_t{0});  // adjacent edges folding back (a spike)
}

double polygon_signed_area(std::span<const Vec2> poly) {
  double a = 0.0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) a += poly[j].x() * poly[i].y() - poly[i].x() * poly[j].y();
  return 0.5 * a;
}

std::vector<std::vector<Vec2>> rectangle_minus_polygon(const Vec2& lo, const Vec2& hi, std::span<const Vec2> polygon,
                                                       bool* holes) {
  namespace bg = boost::geometry;
  using Point = bg::model::d2::point_xy<double>;
  using Poly = bg::model::polygon<Point>;
  Poly rect, cut;
  for (const Vec2& v : {lo, Vec2(lo.x(), hi.y()), hi, Vec2(hi.x(), lo.y()), lo})
    rect.outer().push_back(Point(v.x(), v.y()));
  for (const Vec2& v : polygon) cut.outer().push_back(Point(v.x(), v.y()));
  cut.outer().push_back(Point(polygon[0].x(), polygon[0].y()));
  bg::correct(rect);
  bg::correct(cut);
  bg::model::multi_polygon<Poly> pieces;
  bg::difference(rect, cut, pieces);
  std::vector<std::vector<Vec2>> out;
  if (holes) *holes = false;
  for (const Poly& piece : pieces) {
    if (holes && !piece.inners().empty()) *holes = true;
    std::vector<Vec2> ring;
    for (const Point& p : piece.outer()) ring.emplace_back(p.x(), p.y());
    if (ring.size() > 1 && (ring.front() - ring.back()).norm() == 0.0) ring.pop_back();
    if (ring.size() >= 3) out.push_back(std::move(ring));
  }
  return out;
}

}  // namespace uavplan
