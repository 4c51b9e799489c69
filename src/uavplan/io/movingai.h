// MovingAI benchmark files: 2-D `.map` / `.scen` and 3-D `.3dmap` / `.3dscen`.
// 2-D: x = column, y = row from the top-left; '.', 'G', 'S' free, anything else blocked.
// 3-D: `voxel X Y Z`, then one blocked voxel per line. Readers stream: a map costs one bit per
// cell in memory, whatever the file size. Errors are InputError with the file and line.
#pragma once

#include <string>
#include <vector>

#include "uavplan/planning/search/bit_grid.h"

namespace uavplan {

struct MovingAiProblem {
  int bucket = 0;
  int start[3] = {0, 0, 0};
  int goal[3] = {0, 0, 0};
  double optimal = 0.0;
};

// The largest 3-D map read (the Warframe maps have up to about 90 M voxels).
inline constexpr double kMaxMovingAiVoxels = 1073741824.0;

BitGrid read_movingai_map(const std::string& path);
BitGrid read_movingai_3dmap(const std::string& path);
// 2-D: the bucket is the file's; 3-D files have none: bucket = floor(optimal / 10), -1 when
// the optimal cost is not finite (or beyond 1e7).
std::vector<MovingAiProblem> read_movingai_scen(const std::string& path);
std::vector<MovingAiProblem> read_movingai_3dscen(const std::string& path);

// True for a `.3dmap` path.
bool is_movingai_3d(const std::string& map_path);

// A box of cells [min, max) per axis.
struct CellBox {
  int min[3], max[3];
};
// The blocked cells as boxes, each cell in exactly one: runs along x, rows of equal runs along
// y, then layers of equal rows along z (greedy; far fewer boxes than cells on maps of walls).
std::vector<CellBox> merge_blocked_cells(const BitGrid& grid);

// A scenario of the public contract for one problem on a map: the world is the map's blocked
// cells as boxes of 1 m cells (a 2-D map: a world of zero height), one point UAV (radius 0)
// from the start cell's centre to the goal's, planned by `astar` on the map's own cells
// (cell_m = 1, no climb limit): its grid is the map's, so its lengths are the file's optima
// (any-angle shortcuts may only shorten them).
std::string movingai_scenario_yaml(const BitGrid& grid, const std::vector<CellBox>& boxes, const std::string& name,
                                   const MovingAiProblem& problem);

}  // namespace uavplan
