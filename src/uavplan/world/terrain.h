// Elevation grid ("digital cell map"): each cell holds the height of what stands on it;
// nothing may fly below it.
#pragma once

#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

class TerrainGrid {
 public:
  // heights[j * nx + i] covers x in [x0 + i c, x0 + (i+1) c), y in [y0 + j c, y0 + (j+1) c).
  // `lows`, when given, is each cell's lowest ground (an elevation model's lowest pixel in it; at
  // most its height): what max_agl is measured from. Without it a cell is flat.
  TerrainGrid(Vec2 origin, double cell_m, int nx, int ny, std::vector<double> heights, std::vector<double> lows = {});

  const Vec2& origin() const { return origin_; }
  double cell_m() const { return cell_m_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double height(int i, int j) const { return heights_[static_cast<std::size_t>(j) * nx_ + i]; }
  // The cell's lowest ground (its height where the cell is flat).
  double low(int i, int j) const { return lows_.empty() ? height(i, j) : lows_[static_cast<std::size_t>(j) * nx_ + i]; }
  bool has_lows() const { return !lows_.empty(); }
  double max_height() const { return max_height_; }
  // Height under (x, y); minus infinity outside the grid.
  double height_at(double x, double y) const;
  // The column of cell (i, j) as a box from far below up to its height.
  Aabb column(int i, int j) const;

  // The highest of the cells point_distance(p, reach) looks at: a point more than `reach` above
  // it is farther than reach from every column.
  double highest_near(const Vec2& p, double reach) const;
  // Distance from p to the nearest column, or `cap` when none is closer than cap.
  double point_distance(const Vec3& p, double cap) const;
  // Exact distance from segment [a, b] to the nearest column, or `cap` when none is closer.
  double segment_distance(const Vec3& a, const Vec3& b, double cap) const;
  // Smallest height of segment [a, b] above the cells under it (exact: z is linear along the
  // segment and the cells are flat); +inf where the segment is outside the grid.
  double lowest_height_above(const Vec3& a, const Vec3& b) const;
  // Largest height of segment [a, b] above the lowest ground under it: the cells' lows, `floor_z`
  // beside the grid and where a cell is lower (exact, as lowest_height_above).
  double highest_height_above(const Vec3& a, const Vec3& b, double floor_z) const;

 private:
  Vec2 origin_;
  double cell_m_;
  int nx_, ny_;
  std::vector<double> heights_;
  std::vector<double> lows_;  // empty: the cells are flat
  double max_height_;
};

}  // namespace uavplan
