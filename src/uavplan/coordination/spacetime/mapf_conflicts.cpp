#include "uavplan/coordination/spacetime/mapf_conflicts.h"

#include <algorithm>

namespace uavplan {
namespace {

// Calls found(conflict) for each conflict in time order until it returns false.
template <class Found>
void scan_conflicts(const std::vector<SpaceTimePath>& paths, int vertex_count, Found&& found) {
  const int n = static_cast<int>(paths.size());
  int end = 0;
  for (const SpaceTimePath& p : paths) end = std::max(end, static_cast<int>(p.size()));
  // who[v]: the agent at v at the time being scanned, stamped with that time (time + 1; 0 never).
  std::vector<int> who(static_cast<std::size_t>(vertex_count), -1), when(static_cast<std::size_t>(vertex_count), 0);
  std::vector<int> before(static_cast<std::size_t>(vertex_count), -1),
      before_when(static_cast<std::size_t>(vertex_count), 0);
  for (int t = 0; t < end; ++t) {
    for (int i = 0; i < n; ++i) {
      const int v = vertex_at(paths[i], t);
      if (when[v] == t + 1) {
        if (!found(MapfConflict{who[v], i, t, v, -1})) return;
        continue;
      }
      who[v] = i;
      when[v] = t + 1;
    }
    if (t > 0)
      for (int i = 0; i < n; ++i) {  // swaps between t - 1 and t
        const int from = vertex_at(paths[i], t - 1), to = vertex_at(paths[i], t);
        if (from == to || before_when[to] != t) continue;
        const int j = before[to];
        if (j > i && vertex_at(paths[j], t) == from && !found(MapfConflict{i, j, t - 1, from, to})) return;
      }
    for (int i = 0; i < n; ++i) {
      const int v = vertex_at(paths[i], t);
      before[v] = i;
      before_when[v] = t + 1;
    }
  }
}

}  // namespace

std::optional<MapfConflict> first_conflict(const std::vector<SpaceTimePath>& paths, int vertex_count) {
  std::optional<MapfConflict> first;
  scan_conflicts(paths, vertex_count, [&](const MapfConflict& c) {
    first = c;
    return false;
  });
  return first;
}

int count_conflicts(const std::vector<SpaceTimePath>& paths, int vertex_count) {
  int count = 0;
  scan_conflicts(paths, vertex_count, [&](const MapfConflict&) {
    ++count;
    return true;
  });
  return count;
}

std::optional<std::string> mapf_solution_problem(const SpaceTimeGraph& g, const std::vector<int>& starts,
                                                 const std::vector<int>& goals,
                                                 const std::vector<SpaceTimePath>& paths) {
  if (paths.size() != starts.size()) return "one path per agent expected";
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const SpaceTimePath& p = paths[i];
    const std::string who = "agent " + std::to_string(i);
    if (p.empty() || p.front() != starts[i]) return who + " does not begin at its start";
    if (p.back() != goals[i]) return who + " does not end at its goal";
    for (std::size_t t = 0; t < p.size(); ++t) {
      if (p[t] < 0 || p[t] >= g.vertex_count) return who + " leaves the graph at t = " + std::to_string(t);
      if (t > 0 && p[t] != p[t - 1] && !g.adjacent(p[t - 1], p[t]))
        return who + " jumps between vertices that are not neighbours at t = " + std::to_string(t - 1);
    }
  }
  if (const auto c = first_conflict(paths, g.vertex_count))
    return "agents " + std::to_string(c->a) + " and " + std::to_string(c->b) +
           (c->swap() ? " swap vertices " + std::to_string(c->v) + " and " + std::to_string(c->u) + " at t = "
                      : " meet at vertex " + std::to_string(c->v) + " at t = ") +
           std::to_string(c->t);
  return std::nullopt;
}

int sum_of_costs(const std::vector<SpaceTimePath>& paths) {
  int soc = 0;
  for (const SpaceTimePath& p : paths) soc += static_cast<int>(p.size()) - 1;
  return soc;
}

int makespan(const std::vector<SpaceTimePath>& paths) {
  int m = 0;
  for (const SpaceTimePath& p : paths) m = std::max(m, static_cast<int>(p.size()) - 1);
  return m;
}

}  // namespace uavplan
