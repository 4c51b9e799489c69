#include "uavplan/coordination/spacetime/prioritized.h"

#include <algorithm>
#include <numeric>

#include "uavplan/coordination/spacetime/space_time_astar.h"

namespace uavplan {

MapfResult solve_prioritized(const MapfProblem& problem, const std::vector<std::vector<int>>& lone_h, int orders,
                             const StopCondition& stop) {
  const int n = static_cast<int>(problem.starts.size());
  MapfResult r;
  // First order: the longest lone route first (it has the fewest ways round the others).
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return lone_h[a][problem.starts[a]] > lone_h[b][problem.starts[b]]; });
  SpaceTimeSearch search;
  SpaceTimeTable taken;
  std::vector<SpaceTimePath> paths(static_cast<std::size_t>(n));
  for (int k = 0; k < orders && !stop.should_stop(); ++k) {
    taken.clear(problem.graph.vertex_count, static_cast<std::size_t>(n) * 64);
    int failed = -1;
    for (const int i : order) {
      const SpaceTimeQuery q{problem.starts[i], problem.goals[i], &lone_h[i], &taken, nullptr, 1.0};
      SpaceTimeAnswer a = search.find(problem.graph, q, stop);
      r.low_level_expansions += a.expanded;
      if (!a.found) {
        failed = i;
        break;
      }
      taken.add_path(a.path);
      paths[i] = std::move(a.path);
    }
    if (failed < 0) {
      r.solved = true;
      r.paths = std::move(paths);
      r.method = "prioritized (order " + std::to_string(k + 1) + ")";
      return r;
    }
    std::rotate(order.begin(), std::find(order.begin(), order.end(), failed),
                std::find(order.begin(), order.end(), failed) + 1);  // it goes first next time
  }
  r.why =
      stop.should_stop() ? "stopped" : "no order of the " + std::to_string(orders) + " tried lets every agent through";
  return r;
}

}  // namespace uavplan
