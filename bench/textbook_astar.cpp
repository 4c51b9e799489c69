#include "textbook_astar.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <vector>

namespace uavplan::bench {

TextbookResult textbook_astar(const BitGrid& grid, std::int64_t start, std::int64_t goal) {
  TextbookResult r;
  const auto n = static_cast<std::size_t>(grid.size());
  std::vector<double> g(n, std::numeric_limits<double>::infinity());
  std::vector<std::int64_t> parent(n, -1);
  std::vector<char> closed(n, 0);
  int gx, gy, gz;
  grid.coords(goal, gx, gy, gz);
  auto h = [&](int x, int y, int z) {
    double d[3] = {std::fabs(double(x - gx)), std::fabs(double(y - gy)), std::fabs(double(z - gz))};
    std::sort(d, d + 3);
    return std::sqrt(3.0) * d[0] + std::sqrt(2.0) * (d[1] - d[0]) + (d[2] - d[1]);
  };
  using Item = std::pair<double, std::int64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  g[start] = 0.0;
  int x, y, z;
  grid.coords(start, x, y, z);
  open.push({h(x, y, z), start});
  const int zr = grid.nz() > 1 ? 1 : 0;
  while (!open.empty()) {
    const auto [f, u] = open.top();
    open.pop();
    if (closed[u]) continue;
    closed[u] = 1;
    ++r.expanded;
    if (u == goal) {
      r.found = true;
      r.cost = g[u];
      return r;
    }
    grid.coords(u, x, y, z);
    for (int dz = -zr; dz <= zr; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          bool ok = true;  // every cell of the move's bounding box must be free
          for (int a = 0; a <= (dx != 0) && ok; ++a)
            for (int b = 0; b <= (dy != 0) && ok; ++b)
              for (int c = 0; c <= (dz != 0) && ok; ++c)
                if ((a || b || c) && grid.blocked(x + a * dx, y + b * dy, z + c * dz)) ok = false;
          if (!ok) continue;
          const std::int64_t v = grid.index(x + dx, y + dy, z + dz);
          const double ng = g[u] + std::sqrt(double(dx * dx + dy * dy + dz * dz));
          if (ng < g[v]) {
            g[v] = ng;
            parent[v] = u;
            open.push({ng + h(x + dx, y + dy, z + dz), v});
          }
        }
  }
  return r;
}

}  // namespace uavplan::bench
