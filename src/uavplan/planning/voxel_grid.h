// A voxelisation of the World for grid search: one bit per cell, set when any point of the
// cell lies within the inflation radius of a static obstacle or the terrain (conservative), or
// above the ceiling. Cells tile the bounds exactly; a 2-D world (zero height) has one layer.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/core/vec.h"
#include "uavplan/world/world.h"

namespace uavplan {

class VoxelGrid {
 public:
  VoxelGrid() = default;
  // Cells of about `cell` metres per axis (adjusted so they tile `region`).
  VoxelGrid(const Aabb& region, const Vec3& cell);

  int nx() const { return n_[0]; }
  int ny() const { return n_[1]; }
  int nz() const { return n_[2]; }
  std::int64_t size() const { return static_cast<std::int64_t>(n_[0]) * n_[1] * n_[2]; }
  const Vec3& cell() const { return cell_; }
  const Vec3& origin() const { return origin_; }

  std::int64_t index(int i, int j, int k) const {
    return (static_cast<std::int64_t>(k) * n_[1] + j) * n_[0] + i;
  }
  void coords(std::int64_t idx, int& i, int& j, int& k) const {
    i = static_cast<int>(idx % n_[0]);
    const std::int64_t r = idx / n_[0];
    j = static_cast<int>(r % n_[1]);
    k = static_cast<int>(r / n_[1]);
  }
  bool inside(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < n_[0] && j < n_[1] && k < n_[2];
  }
  Vec3 center(int i, int j, int k) const {
    return origin_ + Vec3((i + 0.5) * cell_.x(), (j + 0.5) * cell_.y(), (k + 0.5) * cell_.z());
  }
  Vec3 center(std::int64_t idx) const {
    int i, j, k;
    coords(idx, i, j, k);
    return center(i, j, k);
  }
  // Cell containing p (clamped into the grid).
  void cell_of(const Vec3& p, int& i, int& j, int& k) const;

  bool blocked(std::int64_t idx) const { return (bits_[idx >> 6] >> (idx & 63)) & 1u; }
  bool blocked(int i, int j, int k) const { return blocked(index(i, j, k)); }
  void set_blocked(std::int64_t idx) { bits_[idx >> 6] |= (std::uint64_t{1} << (idx & 63)); }

 private:
  Vec3 origin_ = Vec3::Zero();
  Vec3 cell_ = Vec3::Ones();
  int n_[3] = {0, 0, 0};
  std::vector<std::uint64_t> bits_;
};

// Marks every cell that is not safe for a UAV of `inflation_m` radius, and every cell whose
// centre lies above `ceiling_m`. Obstacles are rasterised through their bounding boxes, so the
// cost is proportional to the space they cover, not to the grid.
VoxelGrid voxelize(const World& world, const Vec3& cell, double inflation_m, double ceiling_m);

}  // namespace uavplan
