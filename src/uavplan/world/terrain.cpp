#include "uavplan/world/terrain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "uavplan/core/geometry.h"

namespace uavplan {
namespace {
constexpr double kFarBelow_m = -1e12;

// floor(v) clamped to [0, n - 1], safe for infinite v.
int clamp_cell(double v, int n) { return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1))); }
}  // namespace

TerrainGrid::TerrainGrid(Vec2 origin, double cell_m, int nx, int ny, std::vector<double> heights,
                         std::vector<double> lows)
    : origin_(std::move(origin)),
      cell_m_(cell_m),
      nx_(nx),
      ny_(ny),
      heights_(std::move(heights)),
      lows_(std::move(lows)) {
  if (!(cell_m_ > 0.0) || !std::isfinite(cell_m_)) throw std::invalid_argument("terrain cell size must be positive");
  if (nx_ <= 0 || ny_ <= 0) throw std::invalid_argument("terrain grid must have at least one cell");
  if (heights_.size() != static_cast<std::size_t>(nx_) * ny_)
    throw std::invalid_argument("terrain heights do not match the grid size");
  if (!lows_.empty() && lows_.size() != heights_.size())
    throw std::invalid_argument("terrain lows do not match the grid size");
  for (std::size_t k = 0; k < lows_.size(); ++k) lows_[k] = std::min(lows_[k], heights_[k]);
  max_height_ = *std::max_element(heights_.begin(), heights_.end());
}

double TerrainGrid::height_at(double x, double y) const {
  const double fi = std::floor((x - origin_.x()) / cell_m_), fj = std::floor((y - origin_.y()) / cell_m_);
  if (fi < 0 || fj < 0 || fi >= nx_ || fj >= ny_) return -std::numeric_limits<double>::infinity();
  return height(static_cast<int>(fi), static_cast<int>(fj));
}

Aabb TerrainGrid::column(int i, int j) const {
  const double x0 = origin_.x() + i * cell_m_, y0 = origin_.y() + j * cell_m_;
  return {Vec3(x0, y0, kFarBelow_m), Vec3(x0 + cell_m_, y0 + cell_m_, height(i, j))};
}

double TerrainGrid::highest_near(const Vec2& p, double reach) const {
  const int i0 = clamp_cell((p.x() - reach - origin_.x()) / cell_m_, nx_);
  const int i1 = clamp_cell((p.x() + reach - origin_.x()) / cell_m_, nx_);
  const int j0 = clamp_cell((p.y() - reach - origin_.y()) / cell_m_, ny_);
  const int j1 = clamp_cell((p.y() + reach - origin_.y()) / cell_m_, ny_);
  double top = -std::numeric_limits<double>::infinity();
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) top = std::max(top, height(i, j));
  return top;
}

double TerrainGrid::point_distance(const Vec3& p, double cap) const {
  if (p.z() - max_height_ >= cap) return cap;
  const int i0 = clamp_cell((p.x() - cap - origin_.x()) / cell_m_, nx_);
  const int i1 = clamp_cell((p.x() + cap - origin_.x()) / cell_m_, nx_);
  const int j0 = clamp_cell((p.y() - cap - origin_.y()) / cell_m_, ny_);
  const int j1 = clamp_cell((p.y() + cap - origin_.y()) / cell_m_, ny_);
  double best = cap;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) best = std::min(best, column(i, j).distance(p));
  return best;
}

double TerrainGrid::segment_distance(const Vec3& a, const Vec3& b, double cap) const {
  if (std::min(a.z(), b.z()) - max_height_ >= cap) return cap;
  const Vec3 d = b - a;
  // Horizontal reach for choosing cells: every column is within this of the segment, so a larger
  // (or infinite) cap selects nothing more.
  const double span = (nx_ + ny_) * cell_m_ + (a.head<2>() - origin_).norm() + (b.head<2>() - origin_).norm();
  const double reach = std::min(cap, span);
  const double ylo = std::min(a.y(), b.y()) - reach, yhi = std::max(a.y(), b.y()) + reach;
  const int j0 = clamp_cell((ylo - origin_.y()) / cell_m_, ny_);
  const int j1 = clamp_cell((yhi - origin_.y()) / cell_m_, ny_);
  double best = cap;
  for (int j = j0; j <= j1; ++j) {
    // The part of the segment within `cap` of this row, in y.
    const double ry0 = origin_.y() + j * cell_m_ - reach, ry1 = ry0 + cell_m_ + 2 * reach;
    double t0 = 0.0, t1 = 1.0;
    if (std::abs(d.y()) < 1e-300) {
      if (a.y() < ry0 || a.y() > ry1) continue;
    } else {
      double ta = (ry0 - a.y()) / d.y(), tb = (ry1 - a.y()) / d.y();
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      if (t0 > t1) continue;
    }
    const double xa = a.x() + t0 * d.x(), xb = a.x() + t1 * d.x();
    const int i0 = clamp_cell((std::min(xa, xb) - reach - origin_.x()) / cell_m_, nx_);
    const int i1 = clamp_cell((std::max(xa, xb) + reach - origin_.x()) / cell_m_, nx_);
    for (int i = i0; i <= i1; ++i) {
      const double h = height(i, j);
      const Aabb col = column(i, j);
      // Cheap reject: the part of the segment near this column stays `best` above it.
      double ta, tb;
      if (!clip_segment_to_box(a, b, Aabb{col.min.array() - best, col.max.array() + best}, ta, tb)) continue;
      if (std::min(a.z() + ta * d.z(), a.z() + tb * d.z()) - h >= best) continue;
      best = std::min(best, golden_section_min([&](double t) { return col.distance(a + t * d); }, 0.0, 1.0));
      if (best <= 0.0) return 0.0;
    }
  }
  return best;
}

namespace {

// The parameters in (0, 1) where segment [a, b]'s horizontal projection crosses a cell edge of
// the grid, with 0 and 1, sorted.
std::vector<double> cell_cuts(const Vec3& a, const Vec3& b, const Vec2& origin, double cell_m) {
  const Vec2 d = b.head<2>() - a.head<2>();
  std::vector<double> cuts{0.0, 1.0};
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(d[axis]) < 1e-300) continue;
    const double o = origin[axis];
    const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
    for (double k = std::ceil((lo - o) / cell_m); o + k * cell_m < hi; ++k) {
      const double t = (o + k * cell_m - a[axis]) / d[axis];
      if (t > 0.0 && t < 1.0) cuts.push_back(t);
      if (cuts.size() > 1'000'000) break;  // a segment across a million cells: enough
    }
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

}  // namespace

double TerrainGrid::lowest_height_above(const Vec3& a, const Vec3& b) const {
  // In each cell the segment crosses, its lowest point is at one of the two ends of the piece.
  const std::vector<double> cuts = cell_cuts(a, b, origin_, cell_m_);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double tm = 0.5 * (cuts[k] + cuts[k + 1]);
    const Vec3 m = a + tm * (b - a);
    const double h = height_at(m.x(), m.y());
    if (!std::isfinite(h)) continue;
    best = std::min({best, a.z() + cuts[k] * (b.z() - a.z()) - h, a.z() + cuts[k + 1] * (b.z() - a.z()) - h});
  }
  return best;
}

double TerrainGrid::highest_height_above(const Vec3& a, const Vec3& b, double floor_z) const {
  // In each piece the highest point is at one of its ends; the ground there is the cell's
  // height, or the floor beside the grid or above a lower cell.
  const std::vector<double> cuts = cell_cuts(a, b, origin_, cell_m_);
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const Vec3 m = a + 0.5 * (cuts[k] + cuts[k + 1]) * (b - a);
    const double fi = std::floor((m.x() - origin_.x()) / cell_m_), fj = std::floor((m.y() - origin_.y()) / cell_m_);
    const bool on_grid = fi >= 0 && fj >= 0 && fi < nx_ && fj < ny_;
    const double ground = on_grid ? std::max(low(static_cast<int>(fi), static_cast<int>(fj)), floor_z) : floor_z;
    best = std::max({best, a.z() + cuts[k] * (b.z() - a.z()) - ground, a.z() + cuts[k + 1] * (b.z() - a.z()) - ground});
  }
  return best;
}

}  // namespace uavplan
