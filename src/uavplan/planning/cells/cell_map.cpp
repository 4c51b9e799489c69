#include "uavplan/planning/cells/cell_map.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <cstdio>

#include "uavplan/planning/grid_budget.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "uavplan/core/geometry.h"

namespace uavplan {
namespace {

// 2-D distance from the rectangle [lo, hi] to a point.
double rect_point_distance(const Vec2& lo, const Vec2& hi, const Vec2& p) {
  const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
  const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
  return std::hypot(dx, dy);
}

// 2-D distance from the rectangle to a polygon (0 when they overlap).
double rect_polygon_distance(const Vec2& lo, const Vec2& hi, const std::vector<Vec2>& poly) {
  const Vec2 corners[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  if (point_in_polygon(corners[0], poly)) return 0.0;
  double d = World::kInf;
  for (std::size_t a = 0; a < poly.size(); ++a) {
    const Vec2& p = poly[a];
    const Vec2& q = poly[(a + 1) % poly.size()];
    if (rect_point_distance(lo, hi, p) == 0.0) return 0.0;
    for (int e = 0; e < 4; ++e) {
      const Vec2& c = corners[e];
      const Vec2& f = corners[(e + 1) % 4];
      d = std::min(d, segment_segment_distance(Vec3(p.x(), p.y(), 0), Vec3(q.x(), q.y(), 0), Vec3(c.x(), c.y(), 0),
                                               Vec3(f.x(), f.y(), 0)));
    }
  }
  return d;
}

// Footprint distance and top of an obstacle for the cell [lo, hi].
std::pair<double, double> footprint_distance_and_top(const Obstacle& o, const Vec2& lo, const Vec2& hi) {
  return std::visit(
      [&](const auto& s) -> std::pair<double, double> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          return {rect_point_distance(lo, hi, Vec2(s.center.x(), s.center.y())) - s.radius_m,
                  s.center.z() + s.radius_m};
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          return {rect_point_distance(lo, hi, s.center) - s.radius_m, s.z_max_m};
        } else if constexpr (std::is_same_v<T, Box>) {
          const double dx = std::max({s.min.x() - hi.x(), 0.0, lo.x() - s.max.x()});
          const double dy = std::max({s.min.y() - hi.y(), 0.0, lo.y() - s.max.y()});
          return {std::hypot(dx, dy), s.max.z()};
        } else {
          return {rect_polygon_distance(lo, hi, s.polygon), s.z_max_m};
        }
      },
      o);
}

}  // namespace

CellMap::CellMap(const World& world, const CellMapOptions& opt, const StopCondition& stop) {
  const Aabb& b = world.bounds();
  const TerrainGrid* terrain = world.terrain();
  cell_m_ = opt.cell_m > 0.0 ? opt.cell_m
            : terrain        ? terrain->cell_m()
                             : std::max(b.max.x() - b.min.x(), b.max.y() - b.min.y()) / 64.0;
  level_m_ = opt.level_m > 0.0 ? opt.level_m : cell_m_ / 2.0;
  origin_ = Vec2(b.min.x(), b.min.y());
  {  // sized before anything is built (or an int overflows)
    const double nx = std::max(1.0, std::ceil((b.max.x() - b.min.x()) / cell_m_ - kWholeNumberSlack));
    const double ny = std::max(1.0, std::ceil((b.max.y() - b.min.y()) / cell_m_ - kWholeNumberSlack));
    const double nz = std::max(
        1.0,
        std::floor((opt.ceiling_m - opt.inflation_m - b.min.z() - opt.inflation_m) / level_m_ + kWholeNumberSlack) + 1);
    const std::string what = strf("planner.params.cell_m = %g m, level_m = %g m", cell_m_, level_m_);
    // Heights per column, and per node the graph's costs, pheromone and search state.
    require_grid(nx * ny * nz, 48.0, stop, what);
    if (nx * ny * nz > 50'000'000)
      throw std::invalid_argument(std::string(what) + ": a cell map of " + std::to_string(static_cast<long long>(nx)) +
                                  " x " + std::to_string(static_cast<long long>(ny)) + " x " +
                                  std::to_string(static_cast<long long>(nz)) + " cells is too large: raise cell_m");
  }
  nx_ = std::max(1, static_cast<int>(std::ceil((b.max.x() - b.min.x()) / cell_m_ - kWholeNumberSlack)));
  ny_ = std::max(1, static_cast<int>(std::ceil((b.max.y() - b.min.y()) / cell_m_ - kWholeNumberSlack)));
  // Cells must lie inside the bounds: shrink the cell so the grid fits exactly.
  cell_m_ = std::min((b.max.x() - b.min.x()) / nx_, (b.max.y() - b.min.y()) / ny_);
  // A flat world (no height) is one level in its plane: no ground to keep the radius from.
  const bool flat = b.extent().z() <= 0.0;
  z0_ = flat ? b.min.z() : b.min.z() + opt.inflation_m;
  nz_ = flat ? 1
             : std::max(0, static_cast<int>(
                               std::floor((opt.ceiling_m - opt.inflation_m - z0_) / level_m_ + kWholeNumberSlack)) +
                               1);

  const double r = opt.inflation_m;
  // A level exactly at top + r would sit on the boundary of the exact segment check and fail it
  // by rounding (10.501 - 10 < 0.501): free cells keep a micrometre above it.
  constexpr double kAbove_m = 1e-6;
  required_.assign(static_cast<std::size_t>(nx_) * ny_, flat ? b.min.z() : b.min.z() + r);
  for (const Obstacle& o : world.obstacles()) {
    stop.throw_if_stopped();  // a fine map of a city takes seconds to build
    const Aabb ob = bounding_box(o);
    const int i0 = std::max(0, static_cast<int>(std::floor((ob.min.x() - r - origin_.x()) / cell_m_)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((ob.max.x() + r - origin_.x()) / cell_m_)));
    const int j0 = std::max(0, static_cast<int>(std::floor((ob.min.y() - r - origin_.y()) / cell_m_)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((ob.max.y() + r - origin_.y()) / cell_m_)));
    for (int j = j0; j <= j1; ++j) {
      stop.throw_if_stopped();
      for (int i = i0; i <= i1; ++i) {
        const Vec2 lo(origin_.x() + i * cell_m_, origin_.y() + j * cell_m_);
        const Vec2 hi(lo.x() + cell_m_, lo.y() + cell_m_);
        const auto [d, top] = footprint_distance_and_top(o, lo, hi);
        if (d < r || d <= 0.0) {
          double& req = required_[static_cast<std::size_t>(j) * nx_ + i];
          req = std::max(req, top + r + kAbove_m);
        }
      }
    }
  }
  if (terrain) {
    // The highest terrain cell within the inflation of the column.
    for (int j = 0; j < ny_; ++j) {
      stop.throw_if_stopped();
      for (int i = 0; i < nx_; ++i) {
        const double x0 = origin_.x() + i * cell_m_ - r, x1 = x0 + cell_m_ + 2 * r;
        const double y0 = origin_.y() + j * cell_m_ - r, y1 = y0 + cell_m_ + 2 * r;
        const Vec2& to = terrain->origin();
        const double tc = terrain->cell_m();
        const int ti0 = std::max(0, static_cast<int>(std::floor((x0 - to.x()) / tc)));
        const int ti1 = std::min(terrain->nx() - 1, static_cast<int>(std::floor((x1 - to.x()) / tc)));
        const int tj0 = std::max(0, static_cast<int>(std::floor((y0 - to.y()) / tc)));
        const int tj1 = std::min(terrain->ny() - 1, static_cast<int>(std::floor((y1 - to.y()) / tc)));
        double& req = required_[static_cast<std::size_t>(j) * nx_ + i];
        for (int tj = tj0; tj <= tj1; ++tj)
          for (int ti = ti0; ti <= ti1; ++ti) req = std::max(req, terrain->height(ti, tj) + r + kAbove_m);
      }
    }
  }
}

void CellMap::cell_of(const Vec3& p, int& i, int& j) const {
  i = std::clamp(static_cast<int>(std::floor((p.x() - origin_.x()) / cell_m_)), 0, nx_ - 1);
  j = std::clamp(static_cast<int>(std::floor((p.y() - origin_.y()) / cell_m_)), 0, ny_ - 1);
}

}  // namespace uavplan
