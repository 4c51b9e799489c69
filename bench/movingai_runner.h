// Runs a MovingAI map and scenario file through one of our grid searches and, on the same
// problems in the same process, through the textbook A*; returns per-problem results and
// formats the table (by bucket band) and JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uavplan::bench {

struct MovingAiOptions {
  // astar | jps | jps+ (2-D, with its jump table) | jps-forward (3-D, from the start alone) | theta
  std::string algorithm = "astar";
  int limit = 0;          // 0: every problem; else this many, spread evenly
  bool reference = true;  // also run the textbook A*
};

struct MovingAiProblemResult {
  int bucket = 0;
  double optimal = 0.0, cost = 0.0;
  bool solved = false, within = false;  // found, and its cost meets the algorithm's criterion
  double ms = 0.0, ref_ms = 0.0;
  std::uint64_t expanded = 0;
};

struct MovingAiReport {
  std::string map, algorithm;
  bool three_d = false;
  int cells[3] = {0, 0, 0};
  double load_ms = 0.0;
  double preprocess_ms = 0.0, table_mb = 0.0;  // jps+: the jump table, 3-D jps: the bit lines, built once
  bool table_built = false;                    // jps+: false where the grid is too wide for one
  bool reference = true;                       // the textbook A* ran beside ours
  double grid_mb = 0.0, peak_rss_mb = 0.0;
  std::vector<MovingAiProblemResult> problems;

  bool passed() const;  // every problem solved within its criterion
};

// Throws InputError for unreadable files, std::invalid_argument for a bad algorithm.
MovingAiReport run_movingai(const std::string& map_path, const std::string& scen_path, const MovingAiOptions& options);
std::string format_movingai(const MovingAiReport& report);
std::string movingai_json(const MovingAiReport& report);

// Writes a synthetic .3dmap of the Warframe A1 size (896 x 390 x 255) with `blocked` voxels,
// loads it, and returns {resident MB after loading, grid MB}. Call first in a fresh process.
struct MemoryProbe {
  double peak_rss_mb = 0.0, grid_mb = 0.0, file_mb = 0.0, load_ms = 0.0;
  std::int64_t blocked = 0;
};
MemoryProbe probe_a1_memory(const std::string& scratch_path, std::int64_t blocked);

double peak_rss_mb();

}  // namespace uavplan::bench
