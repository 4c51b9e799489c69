#include "uavplan/planning/cells/cell_astar.h"

#include <queue>

namespace uavplan {

CellAStarOptions CellAStarOptions::from_params(const Params& params) {
  ParamReader r(params, "cell_astar");
  CellAStarOptions o;
  o.cells.read(r);
  r.finish();
  return o;
}

std::optional<std::vector<std::int64_t>> cell_astar_search(const CellGraph& g, std::int64_t from, std::int64_t to,
                                                           PlanStats& stats, const StopCondition& stop) {
  const CellMap& m = g.map();
  const auto n = static_cast<std::size_t>(m.nodes());
  std::vector<double> cost(n, World::kInf);
  std::vector<std::int64_t> parent(n, -1);
  std::vector<char> closed(n, 0);
  const Vec3 goal = m.centre(to);
  using Item = std::pair<double, std::int64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  cost[from] = 0.0;
  open.emplace(g.heuristic(m.centre(from), goal), from);
  while (!open.empty()) {
    stats.open_max = std::max<std::uint64_t>(stats.open_max, open.size());
    const auto [f, v] = open.top();
    open.pop();
    if (closed[v]) continue;
    closed[v] = 1;
    if ((++stats.nodes_expanded & 4095) == 0 && stop.should_stop()) return std::nullopt;
    if (v == to) {
      std::vector<std::int64_t> path{to};
      while (path.back() != from) path.push_back(parent[path.back()]);
      std::reverse(path.begin(), path.end());
      return path;
    }
    int i = 0, j = 0, k = 0;
    m.unpack(v, i, j, k);
    const Vec3 pv = m.centre(i, j, k);
    for (int mv = 0; mv < CellGraph::kMoves; ++mv) {
      const std::int64_t w = g.neighbour(i, j, k, mv);
      if (w < 0 || closed[w]) continue;
      const Vec3 pw = m.centre(w);
      const double c = cost[v] + g.cost(pv, pw);
      if (c < cost[w]) {
        cost[w] = c;
        parent[w] = v;
        open.emplace(c + g.heuristic(pw, goal), w);
      }
    }
  }
  return std::nullopt;
}

PlanResult CellAStarPlanner::do_plan(const Problem& problem, const World& world, const StopCondition& stop) const {
  return plan_on_cells(problem, world, options_.cells, stop,
                       // An exact search has no best-so-far: it keeps the whole stop, not a leg's share.
                       [&stop](const CellGraph& g, std::int64_t a, std::int64_t b, int, PlanStats& s,
                               const StopCondition&) { return cell_astar_search(g, a, b, s, stop); });
}

}  // namespace uavplan
