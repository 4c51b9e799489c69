#include "uavplan/planning/voxel_grid.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

namespace uavplan {

VoxelGrid::VoxelGrid(const Aabb& region, const Vec3& cell) : origin_(region.min) {
  const Vec3 ext = region.extent();
  int n[3];
  for (int a = 0; a < 3; ++a) {
    const double want = cell[a] > 0.0 ? cell[a] : 1.0;
    n[a] = std::max(1, static_cast<int>(std::min(std::floor(ext[a] / want + kWholeNumberSlack), 1e9)));
    cell_[a] = ext[a] > 0.0 ? ext[a] / n[a] : 0.0;
  }
  cells_ = BitGrid(n[0], n[1], n[2]);
}

double VoxelGrid::cell_count(const Aabb& region, const Vec3& cell) {
  const Vec3 ext = region.extent();
  double count = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double want = cell[a] > 0.0 ? cell[a] : 1.0;
    count *= std::max(1.0, std::min(std::floor(ext[a] / want + kWholeNumberSlack), 1e9));  // as the constructor
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

namespace {

// Boxes that reach above every voxel centre (the closed sky over a max_agl band: a box per
// terrain cell; tall buildings): below such a box a centre at horizontal distance d < reach is
// blocked exactly when it lies above the box's bottom less sqrt(reach^2 - d^2), so each voxel
// column is blocked from one height up, found in O(1) per box and column instead of a distance
// per voxel. Returns which obstacles were handled so.
std::vector<char> block_under_tall_boxes(const World& world, VoxelGrid& g, double reach) {
  const auto& obstacles = world.obstacles();
  std::vector<char> done(obstacles.size(), 0);
  const double top_centre = g.center_z(g.nz() - 1);
  std::vector<double> from_z;  // per column: the lowest blocked height
  for (std::size_t n = 0; n < obstacles.size(); ++n) {
    const Box* b = std::get_if<Box>(&obstacles[n]);
    if (!b || !(b->max.z() > top_centre)) continue;
    if (from_z.empty()) from_z.assign(static_cast<std::size_t>(g.nx()) * g.ny(), World::kInf);
    done[n] = 1;
    int i0, j0, k0, i1, j1, k1;
    g.cell_of(b->min - Vec3::Constant(reach), i0, j0, k0);
    g.cell_of(b->max + Vec3::Constant(reach), i1, j1, k1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 c = g.center_xy(i, j);
        const Vec2 off = (b->min.head<2>() - c).cwiseMax(c - b->max.head<2>()).cwiseMax(0.0);
        const double d2 = off.squaredNorm();
        if (d2 >= reach * reach) continue;
        double& z = from_z[static_cast<std::size_t>(j) * g.nx() + i];
        z = std::min(z, b->min.z() - std::sqrt(reach * reach - d2));
      }
  }
  if (from_z.empty()) return done;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const double z = from_z[static_cast<std::size_t>(j) * g.nx() + i];
      for (int k = g.nz() - 1; k >= 0 && g.center_z(k) > z; --k) g.set_blocked(g.index(i, j, k));
    }
  return done;
}

}  // namespace

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

  const std::vector<char> roofed = block_under_tall_boxes(world, g, reach);
  for (std::size_t n = 0; n < world.obstacles().size(); ++n) {
    if (roofed[n]) continue;
    const Obstacle& o = world.obstacles()[n];
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
    // bottom up to its first safe cell. Centres in the terrain under them are at distance 0 and
    // those `reach` above the highest cell near them are safe: the exact distance is asked only
    // between.
    for (int j = 0; j < g.ny(); ++j) {
      stop.throw_if_stopped();
      for (int i = 0; i < g.nx(); ++i) {
        const Vec2 c = g.center_xy(i, j);
        const double under = t->height_at(c.x(), c.y()), near_top = t->highest_near(c, reach);
        for (int k = 0; k < g.nz(); ++k) {
          const double z = g.center_z(k);
          if (z > under && (z - near_top >= reach || t->point_distance(Vec3(c.x(), c.y(), z), reach) >= reach)) break;
          g.set_blocked(g.index(i, j, k));
        }
      }
    }
  }
  return g;
}

}  // namespace uavplan
