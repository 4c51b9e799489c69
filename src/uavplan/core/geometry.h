// Exact distance and intersection primitives used by the world's queries and the metrics.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

// Distance from p to segment [a, b]; `t_out` (optional) receives the closest parameter.
// The cell edge that cuts a box of this extent into about `count` cubes, over its non-zero
// dimensions (a flat box into squares); 1 for a point.
inline double cell_for_count_m(const Vec3& extent, double count) {
  double volume = 1.0;
  int dims = 0;
  for (int a = 0; a < 3; ++a)
    if (extent[a] > 0.0) {
      volume *= extent[a];
      ++dims;
    }
  return dims == 0 ? 1.0 : std::pow(volume / count, 1.0 / dims);
}

// The length of the polyline through the points, summed from the first (0 for fewer than two).
inline double polyline_length_m(std::span<const Vec3> points) {
  double len = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) len += (points[i] - points[i - 1]).norm();
  return len;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double* t_out = nullptr);

// Distance between segments [p0, p1] and [q0, q1] (Ericson, Real-Time Collision Detection 5.1.9).
double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

// Minimum of a convex function on [lo, hi] by golden-section search; exact to ~1e-13 of the
// interval, which is what distance-to-a-convex-set along a segment needs. Stops early at 0
// (a distance cannot go lower).
template <class F>
double golden_section_min(F&& f, double lo, double hi) {
  constexpr double kInvPhi = 0.6180339887498949;
  double a = lo, b = hi;
  double c = b - kInvPhi * (b - a), d = a + kInvPhi * (b - a);
  double fc = f(c), fd = f(d);
  double best = std::min({f(lo), f(hi), fc, fd});
  for (int i = 0; i < 64 && best > 0.0 && b - a > 1e-13 * (hi - lo); ++i) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kInvPhi * (b - a);
      fc = f(c);
      best = std::min(best, fc);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kInvPhi * (b - a);
      fd = f(d);
      best = std::min(best, fd);
    }
  }
  return best;
}

// Clips segment a + t (b - a), t in [0, 1], to a box; returns false when it misses.
bool clip_segment_to_box(const Vec3& a, const Vec3& b, const Aabb& box, double& t0, double& t1);

// Even-odd point-in-polygon test (boundary counts as inside within floating error).
bool point_in_polygon(const Vec2& p, std::span<const Vec2> polygon);

// Distance from p to the polygon's boundary.
double point_polygon_boundary_distance(const Vec2& p, std::span<const Vec2> polygon);

// Whether 2-D segments [a, b] and [c, d] intersect (touching counts).
bool segments_intersect_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

// Whether a closed polygon's boundary touches or crosses itself (Boost.Geometry's sectioned
// self-turn search), and if so the first two non-adjacent edges that do (edge k runs from vertex
// k to vertex k + 1; located by a pairwise scan up to kLocatedPolygonVertices vertices; edges 0
// and 0 when not located: a larger polygon, or adjacent edges folding back over each other).
inline constexpr std::size_t kLocatedPolygonVertices = 4096;
std::optional<std::pair<std::size_t, std::size_t>> polygon_self_intersection(std::span<const Vec2> polygon);

// Signed area (positive when counter-clockwise).
double polygon_signed_area(std::span<const Vec2> polygon);

// The rectangle [lo, hi] less a simple polygon (Boost.Geometry's difference), as the outer rings
// of its pieces. A piece with a hole (a polygon that does not reach the rectangle's sides all
// round) is returned whole with `holes` set; callers that cannot fill one refuse it.
std::vector<std::vector<Vec2>> rectangle_minus_polygon(const Vec2& lo, const Vec2& hi, std::span<const Vec2> polygon,
                                                       bool* holes = nullptr);

}  // namespace uavplan
