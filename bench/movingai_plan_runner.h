// `plan` itself on MovingAI maps: each problem of a map's scenario file made a scenario of the
// public contract (the map's blocked cells as boxes, one point UAV; io/movingai.h) and planned
// and verified through the library's one entry point, as `uavplan plan` does, with jump point
// search (astar's default where it applies) and with A* alone.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uavplan::bench {

struct MovingAiPlanOptions {
  int limit = 100;           // this many problems, spread evenly over the file (0: all)
  bool astar_too = true;     // also plan each with jump_points = false
  std::string scenario_out;  // where given: the first problem's scenario is written there
};

struct MovingAiPlanRow {
  double optimal = 0.0;
  struct Run {
    bool solved = false, verified = false;
    bool optimal = false;  // the grid search's route is the file's optimum
    bool within = false;   // the route flown is no longer, and no shorter than the straight line
    double grid_m = 0.0, length_m = 0.0, plan_ms = 0.0, total_ms = 0.0;
    std::uint64_t expanded = 0;
    bool passed() const { return solved && verified && optimal && within; }
  } jps, astar;
};

struct MovingAiPlanReport {
  std::string map;
  int cells[3] = {0, 0, 0};
  std::int64_t blocked = 0;
  std::size_t boxes = 0;
  double yaml_kb = 0.0, load_ms = 0.0, first_plan_ms = 0.0;
  bool astar_too = true;
  std::vector<MovingAiPlanRow> rows;
  std::vector<std::string> misses;  // each problem not solved, verified and within, in words

  bool passed() const;  // every problem solved, verified, optimal on the grid and within
};

// Throws InputError for unreadable files.
MovingAiPlanReport run_movingai_plan(const std::string& map_path, const std::string& scen_path,
                                     const MovingAiPlanOptions& options);
std::string format_movingai_plan(const MovingAiPlanReport& report);

}  // namespace uavplan::bench
