// Jump Point Search on a 2-D BitGrid (nz == 1) with 8 neighbours and no corner cutting (a
// diagonal move needs both orthogonal neighbours free: MovingAI's rule). Optimal; tested
// against GridAStar. Straight jumps stop where a perpendicular neighbour opens up behind a wall
// (its forced neighbour); diagonal jumps stop where a straight jump from them finds anything.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/planning/search/bit_grid.h"
#include "uavplan/planning/search/grid_astar.h"

namespace uavplan {

class Jps2d {
 public:
  // Throws std::invalid_argument unless grid.nz() == 1. The grid must outlive the object.
  explicit Jps2d(const BitGrid& grid);

  // result.cells are the jump points; expand_path() gives every cell.
  GridSearchResult search(std::int64_t start, std::int64_t goal, const StopCondition& stop = {});
  std::vector<std::int64_t> expand_path(const std::vector<std::int64_t>& jump_points) const;

 private:
  struct Expansion;  // jps2d.cpp
  bool free(int x, int y) const { return !grid_->blocked(x, y, 0); }
  bool jump_straight(int& x, int& y, int dx, int dy) const;
  bool jump(int& x, int& y, int dx, int dy) const;
  // The pruned directions from (x, y) reached from `parent`: all eight at the start, else the
  // natural and the forced ones. Returns how many.
  int directions(int x, int y, std::uint32_t parent, int dirs[8][2]) const;

  const BitGrid* grid_;
  int gx_ = 0, gy_ = 0;
  BestFirst<> search_;
};

}  // namespace uavplan
