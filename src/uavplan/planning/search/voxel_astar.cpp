#include "uavplan/planning/search/voxel_astar.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>

namespace uavplan {
namespace {

struct Move {
  int di, dj, dk;
  double cost_m;
  std::vector<std::array<int, 3>> box;  // the cells of the move's bounding box, but the origin
};

std::vector<Move> legal_moves(const VoxelGrid& g, double max_pitch_rad) {
  std::vector<Move> moves;
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        if (!di && !dj && !dk) continue;
        if (g.nz() == 1 && dk) continue;
        const Vec3 d(di * g.cell().x(), dj * g.cell().y(), dk * g.cell().z());
        const double pitch = std::atan2(std::abs(d.z()), d.head<2>().norm());
        if (dk && pitch > max_pitch_rad) continue;
        Move m{di, dj, dk, d.norm(), {}};
        for (int a = 0; a <= (di != 0); ++a)
          for (int b = 0; b <= (dj != 0); ++b)
            for (int c = 0; c <= (dk != 0); ++c)
              if (a || b || c) m.box.push_back({a * di, b * dj, c * dk});
        moves.push_back(std::move(m));
      }
  return moves;
}

struct OpenEntry {
  double f, g;
  std::int64_t idx;
  bool operator<(const OpenEntry& o) const {  // priority_queue is a max-heap: invert
    if (f != o.f) return f > o.f;
    if (g != o.g) return g < o.g;  // deeper first among equal f
    return idx > o.idx;
  }
};

}  // namespace

VoxelPath voxel_astar(const VoxelGrid& grid, std::int64_t start, std::int64_t goal,
                      const VoxelSearchOptions& options, const StopCondition& stop) {
  VoxelPath out;
  if (grid.blocked(start) || grid.blocked(goal)) return out;
  const auto moves = legal_moves(grid, options.max_pitch_rad);
  const Vec3 goal_c = grid.center(goal);
  const auto n = static_cast<std::size_t>(grid.size());
  std::vector<double> g(n, std::numeric_limits<double>::infinity());
  std::vector<std::int64_t> parent(n, -1);
  std::vector<bool> closed(n, false);
  std::priority_queue<OpenEntry> open;
  g[start] = 0.0;
  open.push({(grid.center(start) - goal_c).norm(), 0.0, start});
  while (!open.empty()) {
    out.open_max = std::max<std::uint64_t>(out.open_max, open.size());
    const OpenEntry e = open.top();
    open.pop();
    if (closed[e.idx]) continue;
    closed[e.idx] = true;
    if (e.idx == goal) break;
    if ((++out.expanded & 1023) == 0 && stop.should_stop(out.expanded)) {
      out.stopped = true;
      return out;
    }
    int i, j, k;
    grid.coords(e.idx, i, j, k);
    for (const Move& m : moves) {
      const int ni = i + m.di, nj = j + m.dj, nk = k + m.dk;
      if (!grid.inside(ni, nj, nk)) continue;
      bool free = true;
      for (const auto& c : m.box)
        if (grid.blocked(i + c[0], j + c[1], k + c[2])) { free = false; break; }
      if (!free) continue;
      const std::int64_t nidx = grid.index(ni, nj, nk);
      const double ng = g[e.idx] + m.cost_m;
      if (ng < g[nidx]) {
        g[nidx] = ng;
        parent[nidx] = e.idx;
        open.push({ng + (grid.center(ni, nj, nk) - goal_c).norm(), ng, nidx});
      }
    }
  }
  if (!closed[goal]) return out;
  out.found = true;
  out.cost_m = g[goal];
  for (std::int64_t c = goal; c != -1; c = parent[c]) out.cells.push_back(c);
  std::reverse(out.cells.begin(), out.cells.end());
  return out;
}

}  // namespace uavplan
