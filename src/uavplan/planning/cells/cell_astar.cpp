#include "uavplan/planning/cells/cell_astar.h"

#include <algorithm>

#include "uavplan/planning/search/search_buffers.h"

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
  // Search state in pages touched on first use, stamped per query: a fine map's nodes cost
  // nothing until reached (zeroing 17 bytes per node of a 30 M node map took a second per leg,
  // out of the stop condition's reach).
  thread_local SearchBuffers buf;
  buf.begin(m.nodes());
  const Vec3 goal = m.centre(to);
  const auto cell = [](std::int64_t n) { return static_cast<std::uint32_t>(n); };
  buf.at(cell(from)).g = 0.0;
  buf.push(g.heuristic(m.centre(from), goal), 0.0, cell(from));
  while (!buf.open_empty()) {
    stats.open_max = std::max<std::uint64_t>(stats.open_max, buf.open_size());
    const SearchBuffers::Entry e = buf.pop();
    SearchBuffers::Node& nv = buf.at(e.cell);
    if (SearchBuffers::closed(nv) || e.g > nv.g) continue;
    SearchBuffers::close(nv);
    if ((++stats.nodes_expanded & 4095) == 0 && stop.should_stop()) return std::nullopt;
    const std::int64_t v = e.cell;
    if (v == to) {
      std::vector<std::int64_t> path{to};
      while (path.back() != from) path.push_back(buf.at(cell(path.back())).parent);
      std::reverse(path.begin(), path.end());
      return path;
    }
    int i = 0, j = 0, k = 0;
    m.unpack(v, i, j, k);
    const Vec3 pv = m.centre(i, j, k);
    const double gv = nv.g;
    for (int mv = 0; mv < CellGraph::kMoves; ++mv) {
      const std::int64_t w = g.neighbour(i, j, k, mv);
      if (w < 0) continue;
      SearchBuffers::Node& nw = buf.at(cell(w));
      if (SearchBuffers::closed(nw)) continue;
      const Vec3 pw = m.centre(w);
      const double c = gv + g.cost(pv, pw);
      if (c < nw.g) {
        nw.g = c;
        nw.parent = cell(v);
        buf.push(c + g.heuristic(pw, goal), c, cell(w));
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
