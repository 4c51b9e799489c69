// Whether obstacles wall two points apart, proved without searching for a route: a grid
// planner that finds no route cannot tell a gap narrower than its cells from no gap at all, and
// halving its cells to find out costs it most of its time limit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/core/vec.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct WalledOff {
  bool apart = false;              // proved: no flight of that body joins the two points
  std::vector<std::string> walls;  // the obstacles that close the way (labels), where apart
};

// A flood from a's cell through the faces between cells that a flight could cross. A face is
// closed only when all of it lies within `inflation_m` of one convex obstacle (corner test: an
// inflated convex solid is convex), within it of any obstacle by its centre's distance plus its
// half-diagonal, or above `ceiling_m`; every other face is open. So `apart` is exact where it
// says so (a free way would cross some open face); walls thinner than the cells (about
// max_cells over the bounds) are not proved and leave `apart` false. Throws Stopped.
WalledOff walled_off(const World& world, double inflation_m, double ceiling_m, const Vec3& a, const Vec3& b,
                     std::int64_t max_cells, const StopCondition& stop = {});

}  // namespace uavplan
