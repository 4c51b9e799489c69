// Jump Point Search on a 3-D BitGrid: 26 neighbours costing 1, sqrt 2, sqrt 3, a move legal only
// when every cell of its bounding box is free (MovingAI's 3-D rule). Optimal (tested against
// GridAStar and every MovingAI 3-D optimum).
//
// The pruning is the canonical ordering of Sturtevant and Rabin (2016) carried to 3-D: a path is
// canonical when each move is a sub-move of the one before (its non-zero components a subset of
// the previous move's, same signs), and without obstacles a canonical path is a shortest one.
// A cell reached by move d goes on with d's sub-moves, plus every move e the obstacles force: e
// is forced when no path from the cell before, of at most the cost of d then e, is legal --
// e then d when d is a sub-move of e (the same cost), else the canonical path to the same cell,
// which is strictly shorter. Every optimal path can be swapped into one whose only turns off the
// ordering are forced (each swap puts a larger move first), so the search keeps one.
// Straight moves jump (64 cells a read on bit lines along each axis, a cell tested exactly only
// where its 3x3x3 neighbourhood changes along the line); two- and three-axis moves walk their
// diagonal and, from each cell of it, the walks of their smaller sub-moves, without making the
// cell a node (JPS2's pruning of intermediate jump points). In 3-D such a walk sweeps a plane or a
// volume, so every walk stops where f = g + h would rise above the expanded node's: the cell there
// becomes a node, and the walk goes on only if the search comes back to it (f never falls along a
// walk). A node is a cell; a cell reached again at its best g by another move is expanded again
// for the moves that one adds (once per move at most), so no continuation of an optimal path is lost.
//
// By default a query runs two such searches, one from each end (moves are legal both ways, so a
// route found backwards is a route), a slice of expansions each in turn, and keeps the first to
// close its goal. Where obstacles lengthen the route by a cell or two near one end, the octile
// distance is exact to every cell of the volume of shortest obstacle-free paths from the other
// end, and the search from there must close all of them before its f reaches the optimum; the
// search from the blocked end meets the detour at once. On Warframe's A1 the cheaper direction is
// up to a thousand times cheaper, and either can be. Both are exact, so the race is too; it costs
// at most twice the cheaper one. docs/decisions/0018 compares it with A* on the Warframe maps.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/planning/search/bit_grid.h"
#include "uavplan/planning/search/bit_lines.h"
#include "uavplan/planning/search/grid_astar.h"

namespace uavplan {

// The grid's blocked cells as bit lines along x, y and z (bit_lines.h), what a search reads.
using Jps3dLines = std::array<BitLines, 3>;
Jps3dLines jps3d_lines(const BitGrid& grid);

struct Jps3dOptions {
  bool both_directions = true;          // false: the search from the start alone
  std::uint32_t slice_expansions = 64;  // each direction's turn (counts, not time: deterministic)
};

class Jps3d {
 public:
  // Throws std::invalid_argument when the grid has 2^32 - 1 cells or more. The grid must outlive
  // the object; one object per thread (it owns buffers, one set per direction).
  explicit Jps3d(const BitGrid& grid, Jps3dOptions options = {});
  // The same with the grid's lines built before (jps3d_lines(grid)): a planner keeps them with
  // its grid, so a query does not pay for them.
  Jps3d(const BitGrid& grid, std::shared_ptr<const Jps3dLines> lines, Jps3dOptions options = {});

  // result.cells are the jump points (or, for a route found backwards, the cells where its move
  // changes); expand_path() gives every cell. Counts are both directions' together.
  GridSearchResult search(std::int64_t start, std::int64_t goal, const StopCondition& stop = {});
  std::vector<std::int64_t> expand_path(const std::vector<std::int64_t>& jump_points) const;
  // The bit lines along y and z built once (x's too): memory apart from the search buffers.
  std::size_t line_bytes() const;

 private:
  struct Expansion;  // jps3d.cpp
  // For the cells reached again at their best g by another move (a tie): the moves that reached
  // them at that g, and the moves walked from them. Other cells need no entry: their one move is
  // the end of their parent's walk. Open addressing, stamped per query (nothing cleared between
  // queries), grown by doubling.
  class MoveSets {
   public:
    struct Entry {
      double g;  // the cell's g the sets belong to (an older, worse g's sets are stale)
      std::uint32_t cell, stamp, reached, walked;  // reached, walked: one bit per move
    };
    void begin();
    Entry* find(std::uint32_t cell);
    Entry& at(std::uint32_t cell);  // found or added; invalidated by the next call

   private:
    std::size_t slot(std::uint32_t cell) const;
    std::vector<Entry> slots_;
    std::size_t used_ = 0;
    std::uint32_t stamp_ = 0;
  };
  // A walk from a node stops at the first cell whose f (the node's g, the walk's length, the
  // octile distance on) exceeds f_max, and that cell becomes a node: the walk goes on from there
  // only if the search comes to it. f never falls along a walk, so the cells past it are no nearer.
  struct WalkLimit {
    int from[3], goal[3];
    double g, f_max;
    bool over(const int c[3]) const {
      return g + octile_distance(c[0] - from[0], c[1] - from[1], c[2] - from[2]) +
                 octile_distance(goal[0] - c[0], goal[1] - c[1], goal[2] - c[2]) >
             f_max;
    }
    // How many of the cells cur, cur + step, ... along `axis` through c come before the first past
    // the limit (62 when none of the next 62 is).
    int first_over(const int c[3], int axis, int cur, int step) const;
  };
  // Jumps from (c[0], c[1], c[2]) along `axis` by `step` (+-1): true with c at the goal, the
  // first cell with a forced move or the first past the limit; false where the line ends first.
  bool jump_straight(int c[3], int axis, int step, const WalkLimit& limit) const;
  // One direction's search: from `from` to `to`.
  struct Side {
    BestFirst<> search;
    MoveSets moves;
    std::uint32_t from = 0, to = 0;
    int goal[3] = {0, 0, 0};
    SearchCounts counts;
  };
  void prepare(Side& side, std::int64_t from, std::int64_t to);
  GridSearchResult race(const StopCondition& stop);

  const BitGrid* grid_;
  Jps3dOptions options_;
  std::shared_ptr<const Jps3dLines> lines_;
  Side sides_[2];  // from the start, from the goal
};

}  // namespace uavplan
