#include "uavplan/planning/grid_budget.h"
#include "uavplan/core/text.h"

#include <cstdio>
#include <stdexcept>

namespace uavplan {

void require_grid(double cells, double bytes_per_cell, const StopCondition& stop, const std::string& what) {
  const std::string buf = strf(": a %.3g-cell grid", cells);
  if (!(cells <= kMaxGridCells))
    throw std::invalid_argument(what + buf + " is more than a grid can index (2^31 cells); use larger cells");
  stop.require_memory(static_cast<std::uint64_t>(cells * bytes_per_cell), what + buf);
}

bool grid_fits(double cells, double bytes_per_cell, const StopCondition& stop) {
  if (!(cells <= kMaxGridCells)) return false;
  return stop.memory_cap_bytes() == 0 || cells * bytes_per_cell <= static_cast<double>(stop.memory_cap_bytes());
}

}  // namespace uavplan
