// The graph a space-time search runs on: vertices with their neighbours (compressed rows), each
// move and each wait one time step. A 4-connected grid (MAPF's benchmark) is one such graph.
#pragma once

#include <cstdint>
#include <vector>

namespace uavplan {

struct SpaceTimeGraph {
  int vertex_count = 0;
  std::vector<int> first;  // vertex v's neighbours are next[first[v] .. first[v + 1])
  std::vector<int> next;

  int degree(int v) const { return first[v + 1] - first[v]; }
  bool adjacent(int u, int v) const;
};

// A width x height grid, 4-connected; blocked[y * width + x] marks obstacle cells (no vertex
// leaves or enters them). Vertex of cell (x, y) = y * width + x.
SpaceTimeGraph grid4(int width, int height, const std::vector<char>& blocked);

// Moves from every vertex to `goal` (breadth-first; -1 where it cannot be reached): the exact
// heuristic of a unit-step search.
std::vector<int> distances_to(const SpaceTimeGraph& g, int goal);

}  // namespace uavplan
