#include "uavplan/planning/cells/cell_astar.h"

#include <algorithm>

#include "uavplan/planning/search/best_first.h"

namespace uavplan {

CellAStarOptions CellAStarOptions::from_params(const Params& params) {
  ParamReader r(params, "cell_astar");
  CellAStarOptions o = read(r);
  r.finish();
  return o;
}

CellAStarOptions CellAStarOptions::read(ParamReader& r) {
  CellAStarOptions o;
  o.cells.read(r);
  return o;
}

namespace {

// A cell's neighbours on the graph, each costed by the graph's edge cost.
struct CellExpansion {
  const CellGraph& g;
  const StopCondition& stop;
  // The stop without the expansion count: a count limit belongs to the colony's iterations.
  bool stop_now(std::uint64_t expanded) const { return (expanded & 4095) == 0 && stop.should_stop(); }
  template <class Relax>
  void expand(std::uint32_t v, const SearchBuffers::Node& n, Relax& relax) const {
    const CellMap& m = g.map();
    int i = 0, j = 0, k = 0;
    m.unpack(v, i, j, k);
    const Vec3 pv = m.centre(i, j, k);
    for (int mv = 0; mv < CellGraph::kMoves; ++mv) {
      const std::int64_t w = g.neighbour(i, j, k, mv);
      if (w < 0) continue;
      const Vec3 pw = m.centre(w);
      relax(static_cast<std::uint32_t>(w), n.g + g.cost(pv, pw), v, pw);
    }
  }
};

}  // namespace

std::optional<std::vector<std::int64_t>> cell_astar_search(const CellGraph& g, std::int64_t from, std::int64_t to,
                                                           PlanStats& stats, const StopCondition& stop) {
  const CellMap& m = g.map();
  // Search state in pages touched on first use, stamped per query: a fine map's nodes cost
  // nothing until reached (zeroing 17 bytes per node of a 30 M node map took a second per leg,
  // out of the stop condition's reach).
  thread_local BestFirst<> search;
  search.begin(m.nodes());
  const Vec3 goal = m.centre(to);
  const auto h = [&](const Vec3& p) { return g.heuristic(p, goal); };
  CellExpansion expansion{g, stop};
  SearchCounts counts;
  const auto a = static_cast<std::uint32_t>(from), b = static_cast<std::uint32_t>(to);
  const SearchEnd end = search.run(expansion, h, a, SearchBuffers::kNoParent, m.centre(from), b, counts);
  stats.nodes_expanded += counts.expanded;
  stats.open_max = std::max(stats.open_max, counts.open_max);
  if (end != SearchEnd::goal) return std::nullopt;
  return search.path(a, b);
}

PlanResult CellAStarPlanner::do_plan(const Problem& problem, const World& world, const StopCondition& stop) const {
  return plan_on_cells(problem, world, options_.cells, stop,
                       // An exact search has no best-so-far: it keeps the whole stop, not a leg's share.
                       [&stop](const CellGraph& g, std::int64_t a, std::int64_t b, int, PlanStats& s,
                               const StopCondition&) { return cell_astar_search(g, a, b, s, stop); });
}

}  // namespace uavplan
