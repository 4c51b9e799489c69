#include "uavplan/coordination/spacetime/space_time_graph.h"

#include <algorithm>

namespace uavplan {

bool SpaceTimeGraph::adjacent(int u, int v) const {
  return std::find(next.begin() + first[u], next.begin() + first[u + 1], v) != next.begin() + first[u + 1];
}

SpaceTimeGraph grid4(int width, int height, const std::vector<char>& blocked) {
  SpaceTimeGraph g;
  g.vertex_count = width * height;
  g.first.reserve(static_cast<std::size_t>(g.vertex_count) + 1);
  const auto open = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height &&
           !blocked[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  };
  constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      g.first.push_back(static_cast<int>(g.next.size()));
      if (!open(x, y)) continue;
      for (int k = 0; k < 4; ++k)
        if (open(x + kDx[k], y + kDy[k])) g.next.push_back((y + kDy[k]) * width + x + kDx[k]);
    }
  g.first.push_back(static_cast<int>(g.next.size()));
  return g;
}

std::vector<int> distances_to(const SpaceTimeGraph& g, int goal) {
  std::vector<int> d(static_cast<std::size_t>(g.vertex_count), -1);
  std::vector<int> queue{goal};
  d[static_cast<std::size_t>(goal)] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int u = queue[head];
    for (int k = g.first[u]; k < g.first[u + 1]; ++k) {
      const int v = g.next[k];
      if (d[static_cast<std::size_t>(v)] >= 0) continue;  // the graph is undirected
      d[static_cast<std::size_t>(v)] = d[static_cast<std::size_t>(u)] + 1;
      queue.push_back(v);
    }
  }
  return d;
}

}  // namespace uavplan
