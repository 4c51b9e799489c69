// A voxelisation of the World for grid search: one bit per cell, set when any point of the
// cell lies within the inflation radius of a static obstacle or the terrain (conservative), or
// above the ceiling. Cells tile the bounds exactly; a 2-D world (zero height) has one layer.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/core/vec.h"
#include "uavplan/planning/search/bit_grid.h"
#include "uavplan/world/world.h"

namespace uavplan {

class VoxelGrid {
 public:
  VoxelGrid() = default;
  // Cells of about `cell` metres per axis (adjusted so they tile `region`).
  VoxelGrid(const Aabb& region, const Vec3& cell);
  // How many cells that grid would have, without building it (as a double: it may be huge).
  static double cell_count(const Aabb& region, const Vec3& cell);

  const BitGrid& cells() const { return cells_; }
  int nx() const { return cells_.nx(); }
  int ny() const { return cells_.ny(); }
  int nz() const { return cells_.nz(); }
  std::int64_t size() const { return cells_.size(); }
  const Vec3& cell() const { return cell_; }
  const Vec3& origin() const { return origin_; }

  std::int64_t index(int i, int j, int k) const { return cells_.index(i, j, k); }
  void coords(std::int64_t idx, int& i, int& j, int& k) const { cells_.coords(idx, i, j, k); }
  bool inside(int i, int j, int k) const { return cells_.inside(i, j, k); }
  // The centre's height and its horizontal place alone: the voxelisation's column loops ask
  // these per cell, and a whole Vec3 each time was most of their cost in a sanitizer build.
  double center_z(int k) const { return origin_.z() + (k + 0.5) * cell_.z(); }
  Vec2 center_xy(int i, int j) const {
    return {origin_.x() + (i + 0.5) * cell_.x(), origin_.y() + (j + 0.5) * cell_.y()};
  }
  Vec3 center(int i, int j, int k) const {
    const Vec2 xy = center_xy(i, j);
    return {xy.x(), xy.y(), center_z(k)};
  }
  Vec3 center(std::int64_t idx) const {
    int i, j, k;
    coords(idx, i, j, k);
    return center(i, j, k);
  }
  // Cell containing p (clamped into the grid).
  void cell_of(const Vec3& p, int& i, int& j, int& k) const;

  bool blocked(std::int64_t idx) const { return cells_.blocked(idx); }
  bool blocked(int i, int j, int k) const { return cells_.blocked(i, j, k); }
  void set_blocked(std::int64_t idx, bool b = true) { cells_.set_blocked(idx, b); }
  BitGrid& cells_mut() { return cells_; }

 private:
  Vec3 origin_ = Vec3::Zero();
  Vec3 cell_ = Vec3::Ones();
  BitGrid cells_;
};

// What a free cell promises.
enum class CellRule {
  // Every point of a free cell is at least the inflation from the world (a cell is blocked when
  // its centre lies closer than the inflation plus its half-diagonal): any path inside free
  // cells is safe. Walls proofs and any-angle searches need it.
  whole_cell,
  // Every straight move between the centres of free cells whose bounding box of cells is free
  // (grid search's moves) is at least the inflation from the world. Such a move keeps h, the
  // smallest half cell size, from every cell outside its bounding box, so a cell is blocked
  // only when the world inflated by max(0, inflation - h) reaches into its interior: boxes are
  // tested exactly, other shapes and the terrain by the half-diagonal. A cell beside a wall is
  // free when the UAV fits between the wall and the centre (a MovingAI voxel map made of boxes
  // is searched as the map itself when the inflation is at most half a cell).
  lattice,
};

// Marks every cell that is not safe for a UAV of `inflation_m` radius (by `rule`), and every
// cell whose centre lies above `ceiling_m`. Obstacles are rasterised through their bounding
// boxes, so the cost is proportional to the space they cover, not to the grid.
// Throws Stopped (core/stop.h) when the stop condition holds while it is built.
VoxelGrid voxelize(const World& world, const Vec3& cell, double inflation_m, double ceiling_m,
                   const StopCondition& stop = {}, CellRule rule = CellRule::whole_cell);

}  // namespace uavplan
