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

GridAStar::GridAStar(const BitGrid& grid, std::vector<GridMove> moves, GridHeuristic heuristic, double cx, double cy,
                     double cz)
    : grid_(&grid), moves_(std::move(moves)), heuristic_(heuristic), c_{cx, cy, cz} {
  for (const GridMove& m : moves_) offsets_.push_back(grid.index(m.di, m.dj, m.dk) - grid.index(0, 0, 0));
}

GridSearchResult grid_result(BestFirst<>& search, SearchEnd end, const SearchCounts& counts, std::uint32_t start,
                             std::uint32_t goal) {
  GridSearchResult out;
  out.expanded = counts.expanded;
  out.generated = counts.generated;
  out.opened = counts.opened;
  out.open_max = counts.open_max;
  if (end != SearchEnd::goal) {
    out.fail(end == SearchEnd::stopped ? Reason::stopped : Reason::no_route);
    return out;
  }
  out.succeed();
  out.cost = search.node(goal).g;
  out.cells = search.path(start, goal);
  return out;
}

// The moves of the table whose bounding box is free, each costed by its length.
struct GridAStar::Expansion {
  const GridAStar& self;
  const StopCondition& stop;
  bool stop_now(std::uint64_t expanded) const { return stop_due(stop, expanded, 4096); }
  template <class Relax>
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) const {
    GridCell c;
    self.grid_->coords(id, c.i, c.j, c.k);
    const std::uint32_t mask = self.grid_->free_mask(c.i, c.j, c.k);
    for (std::size_t m = 0; m < self.moves_.size(); ++m) {
      const GridMove& mv = self.moves_[m];
      if ((mask & mv.need) != mv.need) continue;
      relax(static_cast<std::uint32_t>(id + self.offsets_[m]), n.g + mv.cost, id,
            GridCell{c.i + mv.di, c.j + mv.dj, c.k + mv.dk});
    }
  }
};

template <class Heuristic>
GridSearchResult GridAStar::run(std::int64_t start, std::int64_t goal, const Heuristic& h, const StopCondition& stop) {
  GridCell s;
  grid_->coords(start, s.i, s.j, s.k);
  search_.begin(grid_->size());
  Expansion expansion{*this, stop};
  SearchCounts counts;
  const auto from = static_cast<std::uint32_t>(start), to = static_cast<std::uint32_t>(goal);
  const SearchEnd end = search_.run(expansion, h, from, SearchBuffers::kNoParent, s, to, counts);
  return grid_result(search_, end, counts, from, to);
}

GridSearchResult GridAStar::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  const BitGrid& g = *grid_;
  if (!g.free(start) || !g.free(goal)) return {};
  GridCell t;
  g.coords(goal, t.i, t.j, t.k);
  if (heuristic_ == GridHeuristic::octile) return run(start, goal, OctileToGoal{t, c_[0]}, stop);
  return run(start, goal, EuclideanToGoal{t, c_[0], c_[1], c_[2]}, stop);
}

}  // namespace uavplan
