#include "uavplan/planning/search/theta_star.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace uavplan {

bool line_of_sight(const BitGrid& g, const int a[3], const int b[3]) {
  int cur[3] = {a[0], a[1], a[2]};
  std::int64_t len[3], taken[3] = {0, 0, 0};
  int step[3];
  for (int k = 0; k < 3; ++k) {
    len[k] = std::abs(b[k] - a[k]);
    step[k] = b[k] > a[k] ? 1 : -1;
  }
  if (g.blocked(cur[0], cur[1], cur[2])) return false;
  // The segment between centres crosses the n-th boundary of axis k at t = (2n + 1) / (2 len_k):
  // compare those fractions exactly by cross-multiplying.
  for (;;) {
    int best = -1;
    for (int k = 0; k < 3; ++k) {
      if (taken[k] >= len[k]) continue;
      if (best < 0 || (2 * taken[k] + 1) * len[best] < (2 * taken[best] + 1) * len[k]) best = k;
    }
    if (best < 0) return true;  // reached b
    int axes[3], n = 0;
    for (int k = 0; k < 3; ++k)
      if (taken[k] < len[k] && (2 * taken[k] + 1) * len[best] == (2 * taken[best] + 1) * len[k]) axes[n++] = k;
    // Crossing an edge or corner touches every cell around it: all must be free.
    for (int subset = 1; subset < (1 << n); ++subset) {
      int c[3] = {cur[0], cur[1], cur[2]};
      for (int s = 0; s < n; ++s)
        if (subset & (1 << s)) c[axes[s]] += step[axes[s]];
      if (g.blocked(c[0], c[1], c[2])) return false;
    }
    for (int s = 0; s < n; ++s) {
      cur[axes[s]] += step[axes[s]];
      ++taken[axes[s]];
    }
  }
}

LazyThetaStar::LazyThetaStar(const BitGrid& grid)
    : grid_(&grid),
      moves_(bounding_box_moves(grid)),
      grid_search_(grid, bounding_box_moves(grid), GridHeuristic::octile) {
  for (const GridMove& m : moves_) offsets_.push_back(grid.index(m.di, m.dj, m.dk) - grid.index(0, 0, 0));
}

double LazyThetaStar::distance(std::uint32_t a, std::uint32_t b) const {
  int p[3], q[3];
  grid_->coords(a, p[0], p[1], p[2]);
  grid_->coords(b, q[0], q[1], q[2]);
  return std::sqrt(double(p[0] - q[0]) * (p[0] - q[0]) + double(p[1] - q[1]) * (p[1] - q[1]) +
                   double(p[2] - q[2]) * (p[2] - q[2]));
}

bool LazyThetaStar::visible(std::uint32_t a, std::uint32_t b) const {
  int p[3], q[3];
  grid_->coords(a, p[0], p[1], p[2]);
  grid_->coords(b, q[0], q[1], q[2]);
  return line_of_sight(*grid_, p, q);
}

void LazyThetaStar::set_vertex(std::uint32_t cell, std::uint32_t mask) {
  SearchBuffers::Node* n = &buf_.at(cell);
  if (n->parent == cell || visible(n->parent, cell)) return;
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t best_parent = n->parent;
  for (std::size_t m = 0; m < moves_.size(); ++m) {
    if ((mask & moves_[m].need) != moves_[m].need) continue;
    const auto nc = static_cast<std::uint32_t>(cell + offsets_[m]);
    const SearchBuffers::Node& nn = buf_.at(nc);
    n = &buf_.at(cell);  // a page may have been allocated: re-take the reference
    if (SearchBuffers::closed(nn) && nn.g + moves_[m].cost < best) {
      best = nn.g + moves_[m].cost;
      best_parent = nc;
    }
  }
  n->g = best;
  n->parent = best_parent;
}

void LazyThetaStar::relax_neighbours(std::uint32_t cell, std::uint32_t mask, std::uint32_t goal,
                                     GridSearchResult& out) {
  const std::uint32_t parent = buf_.at(cell).parent;
  const double gp = buf_.at(parent).g;
  for (std::size_t m = 0; m < moves_.size(); ++m) {
    if ((mask & moves_[m].need) != moves_[m].need) continue;
    const auto nc = static_cast<std::uint32_t>(cell + offsets_[m]);
    SearchBuffers::Node& nn = buf_.at(nc);
    if (SearchBuffers::closed(nn)) continue;
    const double ng = gp + distance(parent, nc);
    if (ng < nn.g) {
      nn.g = ng;
      nn.parent = parent;
      buf_.push(ng + distance(nc, goal), ng, nc);
      ++out.generated;
    }
  }
}

void LazyThetaStar::keep_pulled_if_shorter(std::int64_t start, std::int64_t goal, const StopCondition& stop,
                                           GridSearchResult& out) {
  const GridSearchResult a = grid_search_.search(start, goal, stop);
  if (!a.found) return;
  std::vector<std::int64_t> pulled{a.cells.front()};
  double len = 0.0;
  for (std::size_t i = 0; i + 1 < a.cells.size();) {
    std::size_t j = i + 1;
    while (j + 1 < a.cells.size() &&
           visible(static_cast<std::uint32_t>(a.cells[i]), static_cast<std::uint32_t>(a.cells[j + 1])))
      ++j;
    len += distance(static_cast<std::uint32_t>(a.cells[i]), static_cast<std::uint32_t>(a.cells[j]));
    pulled.push_back(a.cells[j]);
    i = j;
  }
  if (len < out.cost) {
    out.cost = len;
    out.cells = std::move(pulled);
  }
  out.expanded += a.expanded;
  out.generated += a.generated;
}

GridSearchResult LazyThetaStar::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  GridSearchResult out;
  const BitGrid& g = *grid_;
  if (start < 0 || goal < 0 || start >= g.size() || goal >= g.size() || g.blocked(start) || g.blocked(goal)) return out;
  const auto s0 = static_cast<std::uint32_t>(start), goal_c = static_cast<std::uint32_t>(goal);
  buf_.begin(g.size());
  SearchBuffers::Node& n0 = buf_.at(s0);
  n0.g = 0.0;
  n0.parent = s0;
  buf_.push(distance(s0, goal_c), 0.0, s0);
  while (!buf_.open_empty()) {
    out.open_max = std::max<std::uint64_t>(out.open_max, buf_.open_size());
    const SearchBuffers::Entry e = buf_.pop();
    const SearchBuffers::Node& n = buf_.at(e.cell);
    if (SearchBuffers::closed(n) || e.g > n.g) continue;
    int i, j, k;
    g.coords(e.cell, i, j, k);
    const std::uint32_t mask = g.free_mask(i, j, k);
    set_vertex(e.cell, mask);
    SearchBuffers::close(buf_.at(e.cell));
    if (e.cell == goal_c) break;
    if ((++out.expanded & 1023) == 0 && stop.should_stop(out.expanded)) {
      out.stopped = true;
      return out;
    }
    relax_neighbours(e.cell, mask, goal_c, out);
  }
  SearchBuffers::Node& gn = buf_.at(goal_c);
  if (!SearchBuffers::closed(gn)) return out;
  out.found = true;
  out.cost = gn.g;
  for (std::uint32_t c = goal_c;; c = buf_.at(c).parent) {
    out.cells.push_back(c);
    if (c == s0) break;
  }
  std::reverse(out.cells.begin(), out.cells.end());
  keep_pulled_if_shorter(start, goal, stop, out);
  return out;
}

}  // namespace uavplan
