// P2's digital cell map: the world as a 2.5-D grid holding, per cell, the height a UAV must
// clear to fly over any point of the cell (buildings, no-fly cylinders as "equivalent heights",
// terrain, all inflated by the UAV radius), and the vertical levels a cell route may use.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/core/vec.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct CellMapOptions {
  double cell_m = 0.0;       // horizontal cell size; 0 = the terrain's cell, else bounds / 64
  double level_m = 0.0;      // vertical level spacing; 0 = cell_m / 2
  double inflation_m = 0.0;  // UAV radius plus margin
  double ceiling_m = 0.0;    // highest altitude a route may use (UAV's or the world's top)
};

class CellMap {
 public:
  // Throws std::invalid_argument naming cell_m / level_m when the map would be too large for an
  // index or for the run's memory cap.
  CellMap(const World& world, const CellMapOptions& options, const StopCondition& stop = {});

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int levels() const { return nz_; }
  double cell_m() const { return cell_m_; }
  double level_m() const { return level_m_; }
  Vec2 origin() const { return origin_; }
  std::int64_t nodes() const { return static_cast<std::int64_t>(nx_) * ny_ * nz_; }

  // Height to clear over cell (i, j): the top of everything within the inflation of the
  // cell's column, plus the inflation; the world's floor plus the inflation where nothing is.
  double required_m(int i, int j) const { return required_[static_cast<std::size_t>(j) * nx_ + i]; }
  double level_z(int k) const { return z0_ + k * level_m_; }
  Vec3 centre(int i, int j, int k) const {
    return {origin_.x() + (i + 0.5) * cell_m_, origin_.y() + (j + 0.5) * cell_m_, level_z(k)};
  }
  Vec3 centre(std::int64_t n) const {
    int i = 0, j = 0, k = 0;
    unpack(n, i, j, k);
    return centre(i, j, k);
  }
  bool free(int i, int j, int k) const { return level_z(k) >= required_m(i, j); }

  std::int64_t index(int i, int j, int k) const { return (static_cast<std::int64_t>(k) * ny_ + j) * nx_ + i; }
  void unpack(std::int64_t n, int& i, int& j, int& k) const {
    i = static_cast<int>(n % nx_);
    j = static_cast<int>((n / nx_) % ny_);
    k = static_cast<int>(n / (static_cast<std::int64_t>(nx_) * ny_));
  }
  // The cell holding (x, y), clamped to the grid.
  void cell_of(const Vec3& p, int& i, int& j) const;

 private:
  Vec2 origin_;
  double cell_m_ = 0.0, level_m_ = 0.0, z0_ = 0.0;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<double> required_;
};

}  // namespace uavplan
