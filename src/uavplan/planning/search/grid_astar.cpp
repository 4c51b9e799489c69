#include "uavplan/planning/search/grid_astar.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace uavplan {

std::vector<GridMove> bounding_box_moves(const BitGrid& g, double cx, double cy, double cz, double max_pitch_rad) {
  std::vector<GridMove> moves;
  const int kmax = g.nz() > 1 ? 1 : 0;
  for (int dk = -kmax; dk <= kmax; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        if (!di && !dj && !dk) continue;
        const double x = di * cx, y = dj * cy, z = dk * cz;
        if (dk && std::atan2(std::abs(z), std::hypot(x, y)) > max_pitch_rad) continue;
        std::uint32_t need = 0;
        for (int a = 0; a <= (di != 0); ++a)
          for (int b = 0; b <= (dj != 0); ++b)
            for (int c = 0; c <= (dk != 0); ++c)
              if (a || b || c) need |= 1u << ((c * dk + 1) * 9 + (b * dj + 1) * 3 + (a * di + 1));
        moves.push_back({di, dj, dk, std::sqrt(x * x + y * y + z * z), need});
      }
  return moves;
}

double octile_distance(int dx, int dy, int dz) {
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

GridAStar::GridAStar(const BitGrid& grid, std::vector<GridMove> moves, GridHeuristic heuristic, double cx, double cy,
                     double cz)
    : grid_(&grid), moves_(std::move(moves)), heuristic_(heuristic), c_{cx, cy, cz} {
  for (const GridMove& m : moves_) offsets_.push_back(grid.index(m.di, m.dj, m.dk) - grid.index(0, 0, 0));
}

double GridAStar::h(int i, int j, int k, int gi, int gj, int gk) const {
  if (heuristic_ == GridHeuristic::octile) return c_[0] * octile_distance(gi - i, gj - j, gk - k);
  const double x = (gi - i) * c_[0], y = (gj - j) * c_[1], z = (gk - k) * c_[2];
  return std::sqrt(x * x + y * y + z * z);
}

GridSearchResult GridAStar::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  GridSearchResult out;
  const BitGrid& g = *grid_;
  if (start < 0 || goal < 0 || start >= g.size() || goal >= g.size() || g.blocked(start) || g.blocked(goal)) return out;
  int gi, gj, gk;
  g.coords(goal, gi, gj, gk);
  buf_.begin(g.size());
  {
    int i, j, k;
    g.coords(start, i, j, k);
    buf_.at(static_cast<std::uint32_t>(start)).g = 0.0;
    buf_.push(h(i, j, k, gi, gj, gk), 0.0, static_cast<std::uint32_t>(start));
  }
  while (!buf_.open_empty()) {
    out.open_max = std::max<std::uint64_t>(out.open_max, buf_.open_size());
    const SearchBuffers::Entry e = buf_.pop();
    SearchBuffers::Node& n = buf_.at(e.cell);
    if (SearchBuffers::closed(n) || e.g > n.g) continue;  // stale entry
    SearchBuffers::close(n);
    if (e.cell == goal) break;
    if ((++out.expanded & 4095) == 0 && stop.should_stop(out.expanded)) {
      out.stopped = true;
      return out;
    }
    int i, j, k;
    g.coords(e.cell, i, j, k);
    const std::uint32_t mask = g.free_mask(i, j, k);
    const double gn = n.g;
    for (std::size_t m = 0; m < moves_.size(); ++m) {
      const GridMove& mv = moves_[m];
      if ((mask & mv.need) != mv.need) continue;
      const auto nc = static_cast<std::uint32_t>(e.cell + offsets_[m]);
      SearchBuffers::Node& nn = buf_.at(nc);
      const double ng = gn + mv.cost;
      if (ng < nn.g && !SearchBuffers::closed(nn)) {
        nn.g = ng;
        nn.parent = e.cell;
        buf_.push(ng + h(i + mv.di, j + mv.dj, k + mv.dk, gi, gj, gk), ng, nc);
        ++out.generated;
      }
    }
  }
  SearchBuffers::Node& goal_node = buf_.at(static_cast<std::uint32_t>(goal));
  if (!SearchBuffers::closed(goal_node)) return out;
  out.found = true;
  out.cost = goal_node.g;
  for (std::uint32_t c = static_cast<std::uint32_t>(goal); c != SearchBuffers::kNoParent; c = buf_.at(c).parent)
    out.cells.push_back(c);
  std::reverse(out.cells.begin(), out.cells.end());
  return out;
}

}  // namespace uavplan
