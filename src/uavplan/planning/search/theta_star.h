// Lazy Theta* (Nash, Koenig and Tovey 2010) on a BitGrid of unit cells, 2-D or 3-D: any-angle
// routes whose straight segments are checked exactly against the occupied cells. Grid moves
// follow bounding_box_moves(); the heuristic is Euclidean. Lazy Theta* alone can end slightly
// longer than the grid optimum (seen on 1 of 10,000 Warframe problems), so the search also
// string-pulls the optimal grid path (A* then greedy line of sight, never longer than the grid
// optimum) and returns the shorter of the two.
#pragma once

#include <cstdint>

#include "uavplan/core/stop.h"
#include "uavplan/planning/search/bit_grid.h"
#include "uavplan/planning/search/grid_astar.h"

namespace uavplan {

// Exact line of sight between the centres of cells a and b: false when the segment touches any
// blocked cell, its boundary included (so passing through a corner needs every cell at that
// corner free: the same rule as a diagonal grid move). Integer arithmetic, no tolerance.
bool line_of_sight(const BitGrid& grid, const int a[3], const int b[3]);

class LazyThetaStar {
 public:
  explicit LazyThetaStar(const BitGrid& grid);
  // result.cells are the route's vertices; cost is its Euclidean length in cells.
  GridSearchResult search(std::int64_t start, std::int64_t goal, const StopCondition& stop = {});

 private:
  double distance(std::uint32_t a, std::uint32_t b) const;
  bool visible(std::uint32_t a, std::uint32_t b) const;
  // SetVertex: a node's parent was assumed visible; if not, the best closed grid neighbour.
  void set_vertex(std::uint32_t cell, std::uint32_t mask);
  struct Expansion;  // theta_star.cpp
  // The string-pulled optimal grid path, kept in `out` when shorter.
  void keep_pulled_if_shorter(std::int64_t start, std::int64_t goal, const StopCondition& stop, GridSearchResult& out);

  const BitGrid* grid_;
  std::vector<GridMove> moves_;
  std::vector<std::int64_t> offsets_;
  BestFirst<> search_;
  GridAStar grid_search_;
};

}  // namespace uavplan
