// A* over a VoxelGrid: 26 neighbours, a move is legal only when every cell of its bounding box
// is free (no corner cutting) and its pitch is within the climb limit; cost and heuristic are
// Euclidean metres, so the result is optimal on the grid.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/core/units.h"
#include "uavplan/planning/voxel_grid.h"

namespace uavplan {

struct VoxelSearchOptions {
  double max_pitch_rad = kPi / 2;  // moves steeper than this are not generated
};

struct VoxelPath {
  bool found = false;
  bool stopped = false;                 // the stop condition ended the search
  std::vector<std::int64_t> cells;      // start .. goal
  double cost_m = 0.0;
  std::uint64_t expanded = 0;
  std::uint64_t open_max = 0;
};

VoxelPath voxel_astar(const VoxelGrid& grid, std::int64_t start, std::int64_t goal,
                      const VoxelSearchOptions& options, const StopCondition& stop);

}  // namespace uavplan
