#include "uavplan/planning/search/jps2d.h"

#include <algorithm>
#include <stdexcept>

namespace uavplan {
namespace {
int sign(int v) { return (v > 0) - (v < 0); }
}  // namespace

Jps2d::Jps2d(const BitGrid& grid) : grid_(&grid) {
  if (grid.nz() != 1) throw std::invalid_argument("Jump Point Search here is 2-D: the grid must have one layer");
}

// Straight jump from (x, y) along (dx, dy) (one of them 0); on success (x, y) is the jump point.
bool Jps2d::jump_straight(int& x, int& y, int dx, int dy) const {
  for (;;) {
    x += dx;
    y += dy;
    if (!free(x, y)) return false;
    if (x == gx_ && y == gy_) return true;
    if (dx != 0) {
      if ((free(x, y + 1) && !free(x - dx, y + 1)) || (free(x, y - 1) && !free(x - dx, y - 1))) return true;
    } else {
      if ((free(x + 1, y) && !free(x + 1, y - dy)) || (free(x - 1, y) && !free(x - 1, y - dy))) return true;
    }
  }
}

bool Jps2d::jump(int& x, int& y, int dx, int dy) const {
  if (dx == 0 || dy == 0) return jump_straight(x, y, dx, dy);
  for (;;) {
    if (!(free(x + dx, y) && free(x, y + dy) && free(x + dx, y + dy))) return false;
    x += dx;
    y += dy;
    if (x == gx_ && y == gy_) return true;
    int hx = x, hy = y, vx = x, vy = y;
    if (jump_straight(hx, hy, dx, 0) || jump_straight(vx, vy, 0, dy)) return true;
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
  const int dx = sign(x - px), dy = sign(y - py);
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

// A node's successors are the jump points along its pruned directions.
struct Jps2d::Expansion {
  const Jps2d& self;
  const StopCondition& stop;
  bool stop_now(std::uint64_t expanded) const { return stop_due(stop, expanded, 1024); }
  template <class Relax>
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) const {
    int x, y, k, dirs[8][2];
    self.grid_->coords(id, x, y, k);
    const int nd = self.directions(x, y, n.parent, dirs);
    for (int d = 0; d < nd; ++d) {
      int jx = x, jy = y;
      if (!self.jump(jx, jy, dirs[d][0], dirs[d][1])) continue;
      relax(static_cast<std::uint32_t>(self.grid_->index(jx, jy, 0)), n.g + octile_distance(jx - x, jy - y, 0), id,
            GridCell{jx, jy, 0});
    }
  }
};

GridSearchResult Jps2d::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  const BitGrid& g = *grid_;
  if (start < 0 || goal < 0 || start >= g.size() || goal >= g.size() || g.blocked(start) || g.blocked(goal)) return {};
  GridCell s, t;
  g.coords(goal, t.i, t.j, t.k);
  g.coords(start, s.i, s.j, s.k);
  gx_ = t.i;
  gy_ = t.j;
  search_.begin(g.size());
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
