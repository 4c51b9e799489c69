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
  SearchBuffers::Node& n = search_.node(cell);
  if (n.parent == cell || visible(n.parent, cell)) return;
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t best_parent = n.parent;
  for (std::size_t m = 0; m < moves_.size(); ++m) {
    if ((mask & moves_[m].need) != moves_[m].need) continue;
    const auto nc = static_cast<std::uint32_t>(cell + offsets_[m]);
    const SearchBuffers::Node& nn = search_.node(nc);
    if (SearchBuffers::closed(nn) && nn.g + moves_[m].cost < best) {
      best = nn.g + moves_[m].cost;
      best_parent = nc;
    }
  }
  n.g = best;
  n.parent = best_parent;
}

// A node's free grid neighbours, each offered the node's parent (path 2, assumed visible until
// the neighbour is settled).
struct LazyThetaStar::Expansion {
  LazyThetaStar& self;
  const StopCondition& stop;
  GridCell at{};
  std::uint32_t mask = 0;

  bool stop_now(std::uint64_t expanded) const { return stop_due(stop, expanded, 1024); }
  void settle(std::uint32_t id) {
    self.grid_->coords(id, at.i, at.j, at.k);
    mask = self.grid_->free_mask(at.i, at.j, at.k);
    self.set_vertex(id, mask);
  }
  template <class Relax>
  void expand(std::uint32_t, const SearchBuffers::Node& n, Relax& relax) const {
    const std::uint32_t parent = n.parent;
    const double gp = self.search_.node(parent).g;
    GridCell p;
    self.grid_->coords(parent, p.i, p.j, p.k);
    const std::int64_t id = self.grid_->index(at.i, at.j, at.k);
    for (std::size_t m = 0; m < self.moves_.size(); ++m) {
      const GridMove& mv = self.moves_[m];
      if ((mask & mv.need) != mv.need) continue;
      const GridCell to{at.i + mv.di, at.j + mv.dj, at.k + mv.dk};
      relax(static_cast<std::uint32_t>(id + self.offsets_[m]), gp + EuclideanToGoal{p}(to), parent, to);
    }
  }
};

void LazyThetaStar::keep_pulled_if_shorter(std::int64_t start, std::int64_t goal, const StopCondition& stop,
                                           GridSearchResult& out) {
  const GridSearchResult a = grid_search_.search(start, goal, stop);
  if (!a.solved()) return;
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
  const BitGrid& g = *grid_;
  if (!g.free(start) || !g.free(goal)) return {};
  const auto s0 = static_cast<std::uint32_t>(start), goal_c = static_cast<std::uint32_t>(goal);
  GridCell s, t;
  g.coords(start, s.i, s.j, s.k);
  g.coords(goal, t.i, t.j, t.k);
  search_.begin(g.size());
  Expansion expansion{*this, stop};
  SearchCounts counts;
  const SearchEnd end = search_.run(expansion, EuclideanToGoal{t}, s0, s0, s, goal_c, counts);
  GridSearchResult out = grid_result(search_, end, counts, s0, goal_c);
  if (out.solved()) keep_pulled_if_shorter(start, goal, stop, out);
  return out;
}

}  // namespace uavplan
