#include "uavplan/planning/voxel_grid.h"

#include <algorithm>
#include <cmath>

namespace uavplan {

VoxelGrid::VoxelGrid(const Aabb& region, const Vec3& cell) : origin_(region.min) {
  const Vec3 ext = region.extent();
  int n[3];
  for (int a = 0; a < 3; ++a) {
    const double want = cell[a] > 0.0 ? cell[a] : 1.0;
    n[a] = std::max(1, static_cast<int>(std::min(std::floor(ext[a] / want + 1e-9), 1e9)));
    cell_[a] = ext[a] > 0.0 ? ext[a] / n[a] : 0.0;
  }
  cells_ = BitGrid(n[0], n[1], n[2]);
}

double VoxelGrid::cell_count(const Aabb& region, const Vec3& cell) {
  const Vec3 ext = region.extent();
  double count = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double want = cell[a] > 0.0 ? cell[a] : 1.0;
    count *= std::max(1.0, std::min(std::floor(ext[a] / want + 1e-9), 1e9));  // as the constructor
  }
  return count;
}

void VoxelGrid::cell_of(const Vec3& p, int& i, int& j, int& k) const {
  int* out[3] = {&i, &j, &k};
  const int n[3] = {nx(), ny(), nz()};
  for (int a = 0; a < 3; ++a) {
    const double f = cell_[a] > 0.0 ? std::floor((p[a] - origin_[a]) / cell_[a]) : 0.0;
    *out[a] = static_cast<int>(std::clamp(f, 0.0, static_cast<double>(n[a] - 1)));
  }
}

VoxelGrid voxelize(const World& world, const Vec3& cell, double inflation_m, double ceiling_m,
                   const StopCondition& stop) {
  VoxelGrid g(world.bounds(), cell);
  const Vec3 half = 0.5 * g.cell();
  // A cell is unsafe when its centre is closer than inflation + half-diagonal to an obstacle:
  // then some point of the cell may be within the inflation radius.
  const double reach = inflation_m + half.norm();

  for (int k = 0; k < g.nz(); ++k) {
    if (g.center(0, 0, k).z() <= ceiling_m) continue;
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) g.set_blocked(g.index(i, j, k));
  }

  for (const Obstacle& o : world.obstacles()) {
    const Aabb box = bounding_box(o).inflated(reach);
    int i0, j0, k0, i1, j1, k1;
    g.cell_of(box.min, i0, j0, k0);
    g.cell_of(box.max, i1, j1, k1);
    for (int k = k0; k <= k1; ++k) {
      for (int j = j0; j <= j1; ++j) {
        // A large obstacle (a prism of many vertices) on a fine grid takes a while.
        if (((j - j0) & 15) == 0) stop.throw_if_stopped();
        for (int i = i0; i <= i1; ++i) {
          const std::int64_t idx = g.index(i, j, k);
          if (!g.blocked(idx) && point_distance(o, g.center(i, j, k)) < reach) g.set_blocked(idx);
        }
      }
    }
  }

  if (const TerrainGrid* t = world.terrain()) {
    // Distance to the terrain never decreases with height, so each column is blocked from the
    // bottom up to its first safe cell.
    for (int j = 0; j < g.ny(); ++j) {
      stop.throw_if_stopped();
      for (int i = 0; i < g.nx(); ++i)
        for (int k = 0; k < g.nz(); ++k) {
          if (t->point_distance(g.center(i, j, k), reach) >= reach) break;
          g.set_blocked(g.index(i, j, k));
        }
    }
  }
  return g;
}

}  // namespace uavplan
