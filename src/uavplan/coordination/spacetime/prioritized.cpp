#include "uavplan/coordination/spacetime/prioritized.h"

#include <algorithm>
#include <numeric>

#include "uavplan/coordination/spacetime/space_time_astar.h"

namespace uavplan {

MapfResult solve_prioritized(const SpaceTimeModel& model, int orders, const StopCondition& stop) {
  const int n = model.agent_count();
  MapfResult r;
  // First order: the longest lone route first (it has the fewest ways round the others).
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return model.lone_cost(a) > model.lone_cost(b); });
  SpaceTimeSearches search;
  SpaceTimeTable taken;
  std::vector<SpaceTimePath> paths(static_cast<std::size_t>(n));
  for (int k = 0; k < orders && !stop.should_stop(); ++k) {
    taken.clear(model.vertex_count(), static_cast<std::size_t>(n) * 64);
    int failed = -1;
    for (const int i : order) {
      SpaceTimeAnswer a = model.plan(i, taken, nullptr, 1.0, search, stop);
      r.low_level_expansions += a.expanded;
      if (!a.found) {
        failed = i;
        break;
      }
      model.add_path(i, a.path, taken);
      paths[i] = std::move(a.path);
    }
    if (failed < 0) {
      r.succeed();
      r.paths = std::move(paths);
      r.method = "prioritized (order " + std::to_string(k + 1) + ")";
      return r;
    }
    std::rotate(order.begin(), std::find(order.begin(), order.end(), failed),
                std::find(order.begin(), order.end(), failed) + 1);  // it goes first next time
  }
  if (stop.should_stop())
    r.fail(Reason::stopped, "stopped");
  else
    r.fail(Reason::conflict, "no order of the " + std::to_string(orders) + " tried lets every agent through");
  return r;
}

}  // namespace uavplan
