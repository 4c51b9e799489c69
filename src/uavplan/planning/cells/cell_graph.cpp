#include "uavplan/planning/cells/cell_graph.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cstdlib>

namespace uavplan {

CellGraph::CellGraph(const CellMap& map, const World& world, double speed_mps, const CellCostWeights& w,
                     double max_climb_rad, double ceiling_m)
    : map_(&map),
      world_(&world),
      speed_(speed_mps),
      w1_(w.w1),
      w3_(w.w3),
      floor_z_(world.bounds().min.z()),
      max_climb_rad_(max_climb_rad),
      ceiling_m_(ceiling_m) {
  const double usable = std::max(kTinyDivisor, ceiling_m - floor_z_);
  w2_ = w.w2 >= 0.0 ? w.w2 : w.w1 * speed_mps * speed_mps / (usable * usable);
}

const std::array<std::array<int, 3>, CellGraph::kMoves>& CellGraph::moves() {
  static const auto table = [] {
    std::array<std::array<int, 3>, kMoves> t{};
    int n = 0;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if (di || dj || dk) t[n++] = {di, dj, dk};
    return t;
  }();
  return table;
}

int CellGraph::move_index(int di, int dj, int dk) {
  if (std::abs(di) > 1 || std::abs(dj) > 1 || std::abs(dk) > 1 || (di == 0 && dj == 0 && dk == 0)) return -1;
  const int mv = (dk + 1) * 9 + (dj + 1) * 3 + (di + 1);
  return mv > 13 ? mv - 1 : mv;  // the table skips (0, 0, 0), entry 13 of the full cube
}

std::int64_t CellGraph::neighbour(int i, int j, int k, int m) const {
  const auto& d = moves()[m];
  const int i2 = i + d[0], j2 = j + d[1], k2 = k + d[2];
  const CellMap& c = *map_;
  if (i2 < 0 || j2 < 0 || k2 < 0 || i2 >= c.nx() || j2 >= c.ny() || k2 >= c.levels()) return -1;
  if (!c.free(i2, j2, k2) || c.level_z(k2) > ceiling_m_) return -1;
  if (d[2] != 0) {
    const double horiz = std::hypot(d[0], d[1]) * c.cell_m();
    if (std::atan2(c.level_m(), horiz) > max_climb_rad_ + 1e-12) return -1;
  }
  // The segment's lowest point must clear every column it passes over: the two cells of a
  // straight move, all four around the corner a diagonal move passes through.
  const double low = std::min(c.level_z(k), c.level_z(k2));
  if (low < c.required_m(i, j) || low < c.required_m(i2, j2)) return -1;
  if (d[0] != 0 && d[1] != 0 && (low < c.required_m(i2, j) || low < c.required_m(i, j2))) return -1;
  return c.index(i2, j2, k2);
}

double CellGraph::cost(const Vec3& a, const Vec3& b) const {
  const double s = (b - a).norm();
  const double dt = s / speed_;
  const double ha = a.z() - floor_z_, hb = b.z() - floor_z_;
  double j = w1_ * speed_ * s + w2_ * dt * (ha * ha + ha * hb + hb * hb) / 3.0;
  if (w3_ != 0.0 && !world_->radars().empty()) j += w3_ * world_->threat_integral(a, b) / speed_;
  return j;
}

}  // namespace uavplan
