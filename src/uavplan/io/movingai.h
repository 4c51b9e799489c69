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

}  // namespace uavplan
