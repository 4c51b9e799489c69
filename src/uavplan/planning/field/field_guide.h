// The potential field's way out of a local minimum: a grid A* route over the static world (the
// UAV's inflation, its climb limit and ceiling) with the caller's keep-out discs blocked (in a
// group: the UAVs already at their goals, which never move again). The field then flies the
// route, attracted by a point a little ahead on it (apf.h, FieldFlight), so repulsion and peers
// still shape every step and the step safety stays exact. The grid is only a guide: obstacles
// and keep-outs block the cells whose centre they cover, so no passage is missed, and one up to
// a cell narrower than the exact clearance may be offered and then refused by the step check
// (another stall, another route).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "uavplan/core/vec.h"
#include "uavplan/planning/search/grid_astar.h"
#include "uavplan/planning/voxel_grid.h"
#include "uavplan/vehicle/uav.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct KeepOut {
  Vec3 centre;
  double radius_m = 0.0;
};

class FieldGuide {
 public:
  // Cells of about `cell_m` (coarsened so the grid holds at most `max_cells`); when a query
  // finds no route the grid is refined (halved, at most kRefinements times, within max_cells)
  // for it and the queries after it. Building a grid and searching it honour `stop` (a grid
  // being built throws Stopped, core/stop.h; a search cut short finds no route).
  FieldGuide(const World& world, const UavSpec& uav, double cell_m, std::int64_t max_cells = 2'000'000,
             const StopCondition& stop = {});

  // Cell centres from near `from` to near `goal`, then `goal` itself; empty when the finest
  // grid has no route (or `from` / `goal` have no free cell nearby).
  std::vector<Vec3> route(const Vec3& from, const Vec3& goal, std::span<const KeepOut> keep_out);

  double cell_m() const { return levels_.back()->grid.cell().x(); }

  static constexpr int kRefinements = 2;

 private:
  struct Level {
    Level(const World& world, const UavSpec& uav, const Vec3& cell, const StopCondition& stop);
    VoxelGrid grid;
    GridAStar search;  // reads grid's cells: a Level never moves (held by pointer)
  };
  std::vector<Vec3> route_on(Level& level, const Vec3& from, const Vec3& goal, std::span<const KeepOut> keep_out);

  const World* world_;
  UavSpec uav_;
  std::int64_t max_cells_;
  StopCondition stop_;
  std::vector<std::unique_ptr<Level>> levels_;  // coarse to fine; the last is the one in use
  std::vector<std::int64_t> marked_;            // keep-out cells set for one query, cleared after it
};

}  // namespace uavplan
