#include "uavplan/planning/search/jps2d.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace uavplan {
namespace {

int sign(int v) { return (v > 0) - (v < 0); }

}  // namespace

Jps2d::Jps2d(const BitGrid& grid) : grid_(&grid) {
  if (grid.nz() != 1) throw std::invalid_argument("Jump Point Search here is 2-D: the grid must have one layer");
  rows_ = BitLines(grid, 0);
  cols_ = BitLines(grid, 1);
}

bool Jps2d::precompute() {
  if (JumpTable::fits(*grid_)) table_.emplace(*grid_, rows_, cols_);
  return table_.has_value();
}

// Straight jump from (x, y) along (dx, dy) (one of them 0), from the table or on the rows or
// columns; on success (x, y) is the jump point.
bool Jps2d::jump_straight(int& x, int& y, int dx, int dy) const {
  const bool along_x = dx != 0;
  const int line = along_x ? y : x, step = along_x ? dx : dy;
  int& pos = along_x ? x : y;
  const std::int64_t goal = (along_x ? gy_ : gx_) == line ? (along_x ? gx_ : gy_) : -1;
  if (table_) {
    const std::int32_t s = table_->steps(grid_->index(x, y, 0), JumpTable::direction(dx, dy));
    const std::int64_t ahead = goal < 0 ? -1 : (goal - pos) * step;
    if (ahead > 0 && ahead <= std::abs(s)) {  // the goal comes first
      pos = static_cast<int>(goal);
      return true;
    }
    if (s <= 0) return false;
    pos += s * step;
    return true;
  }
  const LineStop to = scan_line(along_x ? rows_ : cols_, line, pos, step, goal);
  if (!to.jump_point) return false;
  pos = static_cast<int>(to.at);
  return true;
}

// A diagonal jump from the table: its own stop, or earlier where it crosses the goal's row or
// column and a straight jump from there reaches the goal (the goal lies ahead within that
// straight jump's steps).
bool Jps2d::jump_diagonal_table(int& x, int& y, int dx, int dy) const {
  const std::int32_t s = table_->steps(grid_->index(x, y, 0), JumpTable::direction(dx, dy));
  const std::int64_t reach = std::abs(s);
  std::int64_t best = s > 0 ? s : std::numeric_limits<std::int64_t>::max();
  const std::int64_t k_row = static_cast<std::int64_t>(gy_ - y) * dy, k_col = static_cast<std::int64_t>(gx_ - x) * dx;
  if (k_row >= 1 && k_row <= reach && k_row < best) {
    const int cx = x + static_cast<int>(k_row) * dx;
    const std::int64_t ahead = static_cast<std::int64_t>(gx_ - cx) * dx;
    if (ahead == 0 ||
        (ahead > 0 && ahead <= std::abs(table_->steps(grid_->index(cx, gy_, 0), JumpTable::direction(dx, 0)))))
      best = k_row;
  }
  if (k_col >= 1 && k_col <= reach && k_col < best) {
    const int cy = y + static_cast<int>(k_col) * dy;
    const std::int64_t ahead = static_cast<std::int64_t>(gy_ - cy) * dy;
    if (ahead == 0 ||
        (ahead > 0 && ahead <= std::abs(table_->steps(grid_->index(gx_, cy, 0), JumpTable::direction(0, dy)))))
      best = k_col;
  }
  if (best == std::numeric_limits<std::int64_t>::max()) return false;
  x += static_cast<int>(best) * dx;
  y += static_cast<int>(best) * dy;
  return true;
}

// Walks the diagonal from (x, y) and offers what expanding each of its stops would give: the goal
// where the diagonal reaches it, else the straight jumps from the cell that find a jump point.
// Scanning, every diagonal cell is such a candidate and its two straight jumps run once; with
// the table, only the stops it records (or the crossing of the goal's row or column).
template <class Offer>
void Jps2d::walk_diagonal(int x, int y, int dx, int dy, const Offer& offer) const {
  for (;;) {
    if (table_) {
      if (!jump_diagonal_table(x, y, dx, dy)) return;
    } else {
      if (!(free(x + dx, y) && free(x, y + dy) && free(x + dx, y + dy))) return;
      x += dx;
      y += dy;
    }
    if (x == gx_ && y == gy_) {
      offer(x, y);
      return;
    }
    int hx = x, hy = y, vx = x, vy = y;
    if (jump_straight(hx, hy, dx, 0)) offer(hx, hy);
    if (jump_straight(vx, vy, 0, dy)) offer(vx, vy);
  }
}

int Jps2d::directions(int x, int y, std::uint32_t parent, int dirs[8][2]) const {
  int nd = 0;
  if (parent == SearchBuffers::kNoParent) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx || dy) {
          dirs[nd][0] = dx;
          dirs[nd++][1] = dy;
        }
    return nd;
  }
  int px, py, k;
  grid_->coords(parent, px, py, k);
  // The direction of the last step: a jump from the parent runs diagonally first, then straight
  // along the longer axis (a successor found from a diagonal's intermediate cell).
  const int ax = std::abs(x - px), ay = std::abs(y - py);
  const int dx = ax >= ay ? sign(x - px) : 0, dy = ay >= ax ? sign(y - py) : 0;
  if (dx && dy) {
    dirs[nd][0] = dx, dirs[nd++][1] = 0;
    dirs[nd][0] = 0, dirs[nd++][1] = dy;
    dirs[nd][0] = dx, dirs[nd++][1] = dy;
  } else if (dx) {
    dirs[nd][0] = dx, dirs[nd++][1] = 0;
    for (int s = -1; s <= 1; s += 2)
      if (free(x, y + s) && !free(x - dx, y + s)) {
        dirs[nd][0] = 0, dirs[nd++][1] = s;
        dirs[nd][0] = dx, dirs[nd++][1] = s;
      }
  } else {
    dirs[nd][0] = 0, dirs[nd++][1] = dy;
    for (int s = -1; s <= 1; s += 2)
      if (free(x + s, y) && !free(x + s, y - dy)) {
        dirs[nd][0] = s, dirs[nd++][1] = 0;
        dirs[nd][0] = s, dirs[nd++][1] = dy;
      }
  }
  return nd;
}

// A node's successors are the jump points along its pruned directions. Along a diagonal, the
// cells where it would stop are not made nodes (JPS2's pruning of intermediate jump points,
// Harabor and Grastien 2014): the straight jumps from each of them are the node's successors,
// at the cost of the diagonal then the straight run (the octile distance), and the diagonal goes
// on past them. A diagonal move has no forced neighbours without corner cutting, so those
// straight jumps and the diagonal's continuation are all that expanding such a cell would give.
struct Jps2d::Expansion {
  const Jps2d& self;
  const StopCondition& stop;
  bool stop_now(std::uint64_t expanded) const { return stop_due(stop, expanded, 1024); }
  template <class Relax>
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) const {
    int x, y, k, dirs[8][2];
    self.grid_->coords(id, x, y, k);
    const auto offer = [&](int jx, int jy) {
      relax(static_cast<std::uint32_t>(self.grid_->index(jx, jy, 0)), n.g + octile_distance(jx - x, jy - y, 0), id,
            GridCell{jx, jy, 0});
    };
    const int nd = self.directions(x, y, n.parent, dirs);
    for (int d = 0; d < nd; ++d) {
      const int dx = dirs[d][0], dy = dirs[d][1];
      int jx = x, jy = y;
      if (dx != 0 && dy != 0)
        self.walk_diagonal(x, y, dx, dy, offer);
      else if (self.jump_straight(jx, jy, dx, dy))
        offer(jx, jy);
    }
  }
};

GridSearchResult Jps2d::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  const BitGrid& g = *grid_;
  if (!g.free(start) || !g.free(goal)) return {};
  GridCell s, t;
  g.coords(goal, t.i, t.j, t.k);
  g.coords(start, s.i, s.j, s.k);
  gx_ = t.i;
  gy_ = t.j;
  // f never falls from a node to its successors (the octile distance is consistent along jumps),
  // so the open list keeps entries in buckets one cell of f wide and heaps only the one it pops:
  // a heap of tens of entries, not of the whole frontier (10-15 % off the median query on the
  // MovingAI city maps; the same pops, so the same search).
  search_.begin(g.size(), octile_distance(t.i - s.i, t.j - s.j, 0), 1.0);
  Expansion expansion{*this, stop};
  SearchCounts counts;
  const auto from = static_cast<std::uint32_t>(start), to = static_cast<std::uint32_t>(goal);
  const SearchEnd end = search_.run(expansion, OctileToGoal{t, 1.0}, from, SearchBuffers::kNoParent, s, to, counts);
  return grid_result(search_, end, counts, from, to);
}

std::vector<std::int64_t> Jps2d::expand_path(const std::vector<std::int64_t>& jp) const {
  std::vector<std::int64_t> cells;
  if (jp.empty()) return cells;
  cells.push_back(jp[0]);
  for (std::size_t i = 1; i < jp.size(); ++i) {
    int x, y, k, tx, ty;
    grid_->coords(jp[i - 1], x, y, k);
    grid_->coords(jp[i], tx, ty, k);
    while (x != tx || y != ty) {
      x += sign(tx - x);
      y += sign(ty - y);
      cells.push_back(grid_->index(x, y, 0));
    }
  }
  return cells;
}

}  // namespace uavplan
