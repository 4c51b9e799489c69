// The graph P2's ants and the A* baseline search: nodes are the free cells of a CellMap at each
// level; a move goes to one of the 26 extended-Moore neighbours (the eight horizontal ones, each
// also one level up or down, and straight up or down). Edge costs discretise P2's penalty
// J = integral (w1 C^2 + w2 h^2 + w3 f_threat) dt (eq. 1) exactly along each straight move:
//   w1 C^2 dt   with C the speed (range rate):      w1 v^2 (s / v) = w1 v s
//   w2 h^2 dt   with h linear from h_a to h_b:      w2 (s / v) (h_a^2 + h_a h_b + h_b^2) / 3
//   w3 f dt     with f the radars' w / d^4 density:  w3 (integral of f ds) / v
// where s is the move's length and h the height above the world's floor.
#pragma once

#include <array>
#include <cmath>

#include "uavplan/planning/cells/cell_map.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct CellCostWeights {
  double w1 = 1.0;   // range
  double w2 = -1.0;  // altitude; negative = w1 v^2 / H^2, H the usable height (so flying at the
                     // ceiling costs twice flying low per second)
  double w3 = 1.0;   // threat
};

class CellGraph {
 public:
  static constexpr int kMoves = 26;

  CellGraph(const CellMap& map, const World& world, double speed_mps, const CellCostWeights& weights,
            double max_climb_rad, double ceiling_m);

  const CellMap& map() const { return *map_; }
  double w1() const { return w1_; }
  double w2() const { return w2_; }
  double w3() const { return w3_; }

  // The neighbour of node (i, j, k) by move m, or -1 when it is off the grid, not free, above
  // the ceiling, too steep, or the move's straight segment passes over a cell higher than it.
  std::int64_t neighbour(int i, int j, int k, int m) const;
  static const std::array<std::array<int, 3>, kMoves>& moves();
  // The move (di, dj, dk) in the table, or -1 when it is none (a step beyond one cell, or none).
  static int move_index(int di, int dj, int dk);

  double cost(const Vec3& a, const Vec3& b) const;
  // Lower bound of the cost from p to q (the range term of the straight line).
  double heuristic(const Vec3& p, const Vec3& q) const { return w1_ * speed_ * (q - p).norm(); }
  double speed() const { return speed_; }

 private:
  const CellMap* map_;
  const World* world_;
  double speed_, w1_, w2_, w3_, floor_z_, max_climb_rad_, ceiling_m_;
};

}  // namespace uavplan
