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

// How a cell is tested (voxel_grid.h, CellRule): boxes against the cell itself (inflated by
// `box_m`) where `exact_boxes`, everything else by its centre's distance (blocked under `ball_m`).
struct CellTest {
  bool exact_boxes = false;
  double box_m = 0.0;
  double ball_m = 0.0;
};

CellTest cell_test(const VoxelGrid& g, double inflation_m, CellRule rule) {
  const Vec3 half = 0.5 * g.cell();
  if (rule == CellRule::whole_cell) return {false, inflation_m, inflation_m + half.norm()};
  double h = World::kInf;  // the smallest half cell (a 2-D world's zero height aside)
  for (int a = 0; a < 3; ++a)
    if (half[a] > 0.0) h = std::min(h, half[a]);
  const double e = std::max(0.0, inflation_m - (h < World::kInf ? h : 0.0));
  return {true, e, e + half.norm()};
}

// Per axis, how far box b lies outside the cell's span [lo, hi] (negative: how deep it reaches
// in); `inside` stays true while b reaches into the cell's interior on every axis so far (a flat
// box, or a flat cell of a 2-D world, touching counts).
double axis_gap(const Box& b, double lo, double hi, int a, bool& inside) {
  const double gap = std::max(b.min[a] - hi, lo - b.max[a]);
  inside = inside && (gap < 0.0 || (gap == 0.0 && (b.min[a] == b.max[a] || lo == hi)));
  return gap;
}

// Whether box b inflated by e reaches into the interior of the cell [lo, hi].
bool box_reaches(const Box& b, const Vec3& lo, const Vec3& hi, double e) {
  bool inside = true;
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double gap = axis_gap(b, lo[a], hi[a], a, inside);
    if (gap > 0.0) d2 += gap * gap;
  }
  return e > 0.0 ? d2 < e * e : inside;
}

Vec3 cell_low(const VoxelGrid& g, int i, int j, int k) {
  return g.origin() + Vec3(i * g.cell().x(), j * g.cell().y(), k * g.cell().z());
}

// The height above which the centres of column (i, j) are blocked by box b that reaches above
// every centre (World::kInf: none of them).
double roof_from_z(const Box& b, const VoxelGrid& g, int i, int j, const CellTest& t) {
  if (!t.exact_boxes) {
    const Vec2 c = g.center_xy(i, j);
    const Vec2 off = (b.min.head<2>() - c).cwiseMax(c - b.max.head<2>()).cwiseMax(0.0);
    const double d2 = off.squaredNorm();
    return d2 < t.ball_m * t.ball_m ? b.min.z() - std::sqrt(t.ball_m * t.ball_m - d2) : World::kInf;
  }
  const Vec3 lo = cell_low(g, i, j, 0), hi = lo + g.cell();
  bool inside = true;
  double d2 = 0.0;
  for (int a = 0; a < 2; ++a) {
    const double gap = axis_gap(b, lo[a], hi[a], a, inside);
    if (gap > 0.0) d2 += gap * gap;
  }
  const double e = t.box_m, half_z = 0.5 * g.cell().z();
  if (e > 0.0) return d2 < e * e ? b.min.z() - std::sqrt(e * e - d2) - half_z : World::kInf;
  return inside ? b.min.z() - half_z : World::kInf;
}

// Boxes that reach above every voxel centre (the closed sky over a max_agl band: a box per
// terrain cell; tall buildings): under such a box each voxel column is blocked from one height
// up, found in O(1) per box and column instead of a test per voxel. Returns which obstacles
// were handled so.
std::vector<char> block_under_tall_boxes(const World& world, VoxelGrid& g, const CellTest& t) {
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
    g.cell_of(b->min - Vec3::Constant(t.ball_m), i0, j0, k0);
    g.cell_of(b->max + Vec3::Constant(t.ball_m), i1, j1, k1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        double& z = from_z[static_cast<std::size_t>(j) * g.nx() + i];
        z = std::min(z, roof_from_z(*b, g, i, j, t));
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

// A box tested exactly: the cells it reaches along a row of x form one run (the inflated box
// is convex), found from both ends and blocked a word at a time.
void block_box(const Box& b, double e, VoxelGrid& g, const StopCondition& stop) {
  int i0, j0, k0, i1, j1, k1;
  g.cell_of(b.min - Vec3::Constant(e), i0, j0, k0);
  g.cell_of(b.max + Vec3::Constant(e), i1, j1, k1);
  const auto reaches = [&](int i, int j, int k) {
    const Vec3 lo = cell_low(g, i, j, k);
    return box_reaches(b, lo, lo + g.cell(), e);
  };
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j) {
      if (((j - j0) & 255) == 0) stop.throw_if_stopped();
      int from = i0, to = i1;
      while (from <= to && !reaches(from, j, k)) ++from;
      while (to > from && !reaches(to, j, k)) --to;
      if (from <= to) g.cells_mut().set_blocked_run(g.index(from, j, k), to - from + 1);
    }
}

// Every cell obstacle o blocks, tested over the cells its bounding box reaches.
void block_near(const Obstacle& o, const CellTest& t, VoxelGrid& g, const StopCondition& stop) {
  if (const Box* box = t.exact_boxes ? std::get_if<Box>(&o) : nullptr) return block_box(*box, t.box_m, g, stop);
  const Aabb reach = bounding_box(o).inflated(t.ball_m);
  int i0, j0, k0, i1, j1, k1;
  g.cell_of(reach.min, i0, j0, k0);
  g.cell_of(reach.max, i1, j1, k1);
  for (int k = k0; k <= k1; ++k) {
    for (int j = j0; j <= j1; ++j) {
      // A large obstacle (a prism of many vertices) on a fine grid takes a while.
      if (((j - j0) & 15) == 0) stop.throw_if_stopped();
      for (int i = i0; i <= i1; ++i) {
        const std::int64_t idx = g.index(i, j, k);
        if (!g.blocked(idx) && point_distance(o, g.center(i, j, k)) < t.ball_m) g.set_blocked(idx);
      }
    }
  }
}

// Distance to the terrain never decreases with height, so each column is blocked from the
// bottom up to its first safe cell. Centres in the terrain under them are at distance 0 and
// those `reach` above the highest cell near them are safe: the exact distance is asked only
// between.
void block_terrain(const TerrainGrid& t, double reach, VoxelGrid& g, const StopCondition& stop) {
  for (int j = 0; j < g.ny(); ++j) {
    stop.throw_if_stopped();
    for (int i = 0; i < g.nx(); ++i) {
      const Vec2 c = g.center_xy(i, j);
      const double under = t.height_at(c.x(), c.y()), near_top = t.highest_near(c, reach);
      for (int k = 0; k < g.nz(); ++k) {
        const double z = g.center_z(k);
        if (z > under && (z - near_top >= reach || t.point_distance(Vec3(c.x(), c.y(), z), reach) >= reach)) break;
        g.set_blocked(g.index(i, j, k));
      }
    }
  }
}

}  // namespace

VoxelGrid voxelize(const World& world, const Vec3& cell, double inflation_m, double ceiling_m,
                   const StopCondition& stop, CellRule rule) {
  VoxelGrid g(world.bounds(), cell);
  const CellTest test = cell_test(g, inflation_m, rule);
  for (int k = 0; k < g.nz(); ++k) {
    if (g.center(0, 0, k).z() <= ceiling_m) continue;
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) g.set_blocked(g.index(i, j, k));
  }
  const std::vector<char> roofed = block_under_tall_boxes(world, g, test);
  for (std::size_t n = 0; n < world.obstacles().size(); ++n)
    if (!roofed[n]) block_near(world.obstacles()[n], test, g, stop);
  if (const TerrainGrid* t = world.terrain()) block_terrain(*t, test.ball_m, g, stop);
  return g;
}

}  // namespace uavplan
