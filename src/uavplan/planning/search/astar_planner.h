// Planner `astar`: an optimal grid search on a voxelisation of the World (inflated by the UAV
// radius), 26 neighbours, then shortcutting with exact segment checks and turn shaping. The
// default resolution comes from the world's size (see auto_cell_m); when the search finds no
// route on the derived grid it refines it, so narrow passages are found without tuning.
// The search is jump point search where it applies and finds the same lengths (cubic cells and
// no climb limit: 3-D JPS from both ends; square cells of a 2-D world: 2-D JPS), else A*.
#pragma once

#include <cstdint>

#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"
#include "uavplan/planning/voxel_grid.h"

namespace uavplan {

struct AStarOptions {
  double cell_m = 0.0;                    // horizontal cell size; 0 = derived from the world
  bool shortcut = true;                   // remove redundant waypoints afterwards
  int refinements = 2;                    // with a derived cell: halve it this often when no route
  std::int64_t max_cells = 8'000'000;     // refinement never exceeds this grid size
  std::int64_t target_cells = 1'000'000;  // derived cells aim at about this many voxels
  bool jump_points = true;                // JPS where it applies (same lengths), else A*

  static AStarOptions from_params(const Params& params);
  // The declaration of its parameters: reads them from r (params.h).
  static AStarOptions read(ParamReader& r);
};

// The derived cell size: about `target_cells` voxels over the world's bounds, no coarser than
// the terrain's cells (so the cell map is resolved) and no finer than half the UAV radius.
double auto_cell_m(const World& world, double radius_m, std::int64_t target_cells);

// Vertical cell size for a horizontal one: diagonal climbing moves must respect the climb
// limit, so layers are thinner when the limit is below 45 degrees.
double layer_height_m(double cell_m, double max_climb_rad);

// Which search a grid gets: jump point search needs every move of its lattice at the octile
// costs (cubic cells with vertical moves allowed, or square cells of one layer).
enum class GridEngine { astar, jps2d, jps3d };
GridEngine grid_engine(const VoxelGrid& grid, double max_climb_rad, bool jump_points);

class AStarPlanner final : public Planner {
 public:
  explicit AStarPlanner(AStarOptions options = {}) : options_(options) {}
  std::string_view name() const override { return "astar"; }
  const AStarOptions& options() const { return options_; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  AStarOptions options_;
};

}  // namespace uavplan
