// A* on a BitGrid with a table of moves: 8 neighbours in 2-D, 26 in 3-D, a move legal only when
// every cell of its bounding box is free (no corner cutting; MovingAI's rule), optionally
// limited in pitch. Reusable buffers (SearchBuffers) make a query cost what it explores, not
// the grid's size. Optimal for the move costs (tested against Dijkstra and MovingAI optima).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "uavplan/core/status.h"
#include "uavplan/core/stop.h"
#include "uavplan/core/units.h"
#include "uavplan/planning/search/best_first.h"
#include "uavplan/planning/search/bit_grid.h"

namespace uavplan {

struct GridMove {
  int di, dj, dk;
  double cost;
  std::uint32_t need;  // free_mask bits that must be set: the move's bounding box
};

// Moves between cells of size (cx, cy, cz), costed by Euclidean length; climbing moves steeper
// than max_pitch_rad are left out. A grid with nz == 1 gets the 8 planar moves.
std::vector<GridMove> bounding_box_moves(const BitGrid& grid, double cx = 1, double cy = 1, double cz = 1,
                                         double max_pitch_rad = kPi / 2);

enum class GridHeuristic {
  octile,     // exact obstacle-free distance for cubic cells (2-D and 3-D octile)
  euclidean,  // admissible for any cell shape and for any-angle paths
};

// solved, or failed for no_route (the goal cannot be reached) or stopped.
struct GridSearchResult : Outcome {
  std::vector<std::int64_t> cells;  // start .. goal (for JPS: the jump points)
  double cost = 0.0;
  std::uint64_t expanded = 0;
  std::uint64_t generated = 0;  // entries pushed (SearchCounts)
  std::uint64_t opened = 0;     // distinct cells put on the list
  std::uint64_t open_max = 0;
};

// A search's end on `search` as a result: counts, and the path along the parents when found.
GridSearchResult grid_result(BestFirst<>& search, SearchEnd end, const SearchCounts& counts, std::uint32_t start,
                             std::uint32_t goal);

class GridAStar {
 public:
  // The grid must outlive the search object. One object per thread (it owns buffers).
  GridAStar(const BitGrid& grid, std::vector<GridMove> moves, GridHeuristic heuristic, double cx = 1, double cy = 1,
            double cz = 1);

  GridSearchResult search(std::int64_t start, std::int64_t goal, const StopCondition& stop = {});
  std::size_t buffer_bytes() const { return search_.memory_bytes(); }

 private:
  struct Expansion;  // grid_astar.cpp
  template <class Heuristic>
  GridSearchResult run(std::int64_t start, std::int64_t goal, const Heuristic& h, const StopCondition& stop);

  const BitGrid* grid_;
  std::vector<GridMove> moves_;
  std::vector<std::int64_t> offsets_;
  GridHeuristic heuristic_;
  double c_[3];
  BestFirst<> search_;
};

// Octile distance between cells for cubic cells of size 1 (inline: every JPS successor and A*
// child takes one).
inline double octile_distance(int dx, int dy, int dz) {
  constexpr double kS2 = 1.4142135623730951, kS3 = 1.7320508075688772;
  if (dz == 0) {
    const int a = std::abs(dx), b = std::abs(dy);
    return a < b ? (kS2 - 1.0) * a + b : (kS2 - 1.0) * b + a;
  }
  int a = std::abs(dx), b = std::abs(dy), c = std::abs(dz);
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);  // a <= b <= c
  return kS3 * a + kS2 * (b - a) + (c - b);
}

struct GridCell {
  int i, j, k;
};
// Lower bounds on the cost from a cell to `goal`, for cells of size (cx, cy, cz).
struct OctileToGoal {  // exact without obstacles for cubic cells (cx the cell size)
  GridCell goal;
  double cx = 1.0;
  double operator()(const GridCell& c) const { return cx * octile_distance(goal.i - c.i, goal.j - c.j, goal.k - c.k); }
};
struct EuclideanToGoal {  // any cell shape, any-angle paths
  GridCell goal;
  double cx = 1.0, cy = 1.0, cz = 1.0;
  double operator()(const GridCell& c) const {
    const double x = (goal.i - c.i) * cx, y = (goal.j - c.j) * cy, z = (goal.k - c.k) * cz;
    return std::sqrt(x * x + y * y + z * z);
  }
};

}  // namespace uavplan
