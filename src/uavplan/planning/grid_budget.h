// Grids and graphs are sized before they are built: more cells than an index holds, or more
// memory than the run may use (StopCondition::memory_cap_bytes, the CLI's --max-memory), is an
// error naming the parameter that asked for it, never std::bad_alloc.
#pragma once

#include <string>

#include "uavplan/core/stop.h"

namespace uavplan {

// The most cells a grid may index (32-bit cell indices).
inline constexpr double kMaxGridCells = 2147483647.0;

// Throws std::invalid_argument "<what>: a N-cell grid ..." when the grid is too large.
void require_grid(double cells, double bytes_per_cell, const StopCondition& stop, const std::string& what);
// Whether require_grid would pass: a refinement that would not fit is not tried (the coarser
// attempt's failure stands), where a first grid that does not fit is an error.
bool grid_fits(double cells, double bytes_per_cell, const StopCondition& stop);

}  // namespace uavplan
