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

GridSearchResult Jps2d::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  GridSearchResult out;
  const BitGrid& g = *grid_;
  if (start < 0 || goal < 0 || start >= g.size() || goal >= g.size() || g.blocked(start) || g.blocked(goal)) return out;
  int k;
  g.coords(goal, gx_, gy_, k);
  buf_.begin(g.size());
  auto h = [&](int x, int y) { return octile_distance(gx_ - x, gy_ - y, 0); };
  {
    int sx, sy;
    g.coords(start, sx, sy, k);
    buf_.at(static_cast<std::uint32_t>(start)).g = 0.0;
    buf_.push(h(sx, sy), 0.0, static_cast<std::uint32_t>(start));
  }
  int dirs[8][2];
  while (!buf_.open_empty()) {
    out.open_max = std::max<std::uint64_t>(out.open_max, buf_.open_size());
    const SearchBuffers::Entry e = buf_.pop();
    SearchBuffers::Node& n = buf_.at(e.cell);
    if (SearchBuffers::closed(n) || e.g > n.g) continue;
    SearchBuffers::close(n);
    if (e.cell == goal) break;
    if ((++out.expanded & 1023) == 0 && stop.should_stop(out.expanded)) {
      out.stopped = true;
      return out;
    }
    int x, y;
    g.coords(e.cell, x, y, k);
    const int nd = directions(x, y, n.parent, dirs);
    for (int d = 0; d < nd; ++d) {
      int jx = x, jy = y;
      if (!jump(jx, jy, dirs[d][0], dirs[d][1])) continue;
      const auto jc = static_cast<std::uint32_t>(g.index(jx, jy, 0));
      SearchBuffers::Node& jn = buf_.at(jc);
      if (SearchBuffers::closed(jn)) continue;
      const double ng = n.g + octile_distance(jx - x, jy - y, 0);
      if (ng < jn.g) {
        jn.g = ng;
        jn.parent = e.cell;
        buf_.push(ng + h(jx, jy), ng, jc);
        ++out.generated;
      }
    }
  }
  SearchBuffers::Node& gn = buf_.at(static_cast<std::uint32_t>(goal));
  if (!SearchBuffers::closed(gn)) return out;
  out.found = true;
  out.cost = gn.g;
  for (std::uint32_t c = static_cast<std::uint32_t>(goal); c != SearchBuffers::kNoParent; c = buf_.at(c).parent)
    out.cells.push_back(c);
  std::reverse(out.cells.begin(), out.cells.end());
  return out;
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
