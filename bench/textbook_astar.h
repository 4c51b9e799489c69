// The yardstick: a textbook A* as found in course notes and most repositories. A binary heap
// (std::priority_queue), fresh buffers for every query, the octile heuristic, neighbours
// checked cell by cell. Same move rules as ours (8 / 26 neighbours, no corner cutting), so its
// costs are optimal too; only its speed is the point.
#pragma once

#include <cstdint>

#include "uavplan/planning/search/bit_grid.h"

namespace uavplan::bench {

struct TextbookResult {
  bool found = false;
  double cost = 0.0;
  std::uint64_t expanded = 0;
};

TextbookResult textbook_astar(const BitGrid& grid, std::int64_t start, std::int64_t goal);

}  // namespace uavplan::bench
