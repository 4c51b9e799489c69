// A sweep: the experiments a batch runs, as the cartesian product of scenarios, planners (each
// with its own parameter grid), a shared parameter grid and seeds. Loaded from YAML:
//
//   name: p4-grid                 # optional; the experiment's name (default: the file's stem)
//   scenarios: [a.yaml, "maps/*.yaml"]   # files or globs, relative to the sweep file
//   planners: [astar, {name: rrt, params: {goal_bias: [0.05, 0.2]}}]   # default: each scenario's own
//   seeds: 10                     # a count (seeds 1..10) or a list [3, 7]; default 1
//   params: {cell_m: [2, 4], "uavs[0].speed": [5]}   # --set keys, each a list of values
//   time_limit_s: 30              # per run; optional
//
// Runs are numbered in a fixed order (scenario, planner, parameters, seed), so a run's number,
// its results and its plan file are the same whoever runs it and in whatever order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace uavplan {

using ParamSetting = std::vector<std::pair<std::string, std::string>>;  // key, value (as --set)

struct GridEntry {
  std::string key;
  std::vector<std::string> values;
  int line = 0;  // in the sweep file
};
using ParamGrid = std::vector<GridEntry>;

struct SweepPlanner {
  std::string name;  // empty: the scenario's own planner
  ParamGrid params;
  int line = 0;
};

struct Sweep {
  std::string name;
  std::string source;                  // the sweep file
  std::vector<std::string> scenarios;  // paths, in the order given (globs sorted)
  std::vector<int> scenario_lines;
  std::vector<SweepPlanner> planners;
  std::vector<std::uint64_t> seeds;
  ParamGrid params;
  double time_limit_s = 0.0;  // 0: none
};

struct RunSpec {
  std::size_t index = 0;
  std::string scenario;              // path
  std::string scenario_fingerprint;  // of the file's content when the runs were listed (files.h)
  std::string planner;               // empty: the scenario's own
  std::uint64_t seed = 1;
  ParamSetting params;  // shared grid first, then the planner's own
};

// Throws InputError (file, line, key, what) for a malformed sweep, a scenario file that is
// missing or a glob that matches none, an unknown planner, or an empty product.
Sweep parse_sweep(const std::string& text, const std::string& source_path);
Sweep load_sweep(const std::string& path);

// Loads every scenario and checks every planner and parameter against it: throws InputError
// naming the sweep file, the line and key (scenarios[1], planners[0], params.cell_m) for a
// scenario that does not load, a planner that cannot plan a scenario's mission, or a parameter
// no planner or mission of the product takes (or a value it refuses).
void check_sweep(const Sweep& sweep);

// Every run of the sweep, numbered from 0, each with its scenario file's fingerprint.
std::vector<RunSpec> expand_runs(const Sweep& sweep);
std::size_t run_count(const Sweep& sweep);
// Settings a grid spans (the product of its value counts; 1 for none).
std::size_t grid_size(const ParamGrid& grid);

// "cell_m=2;goal_bias=0.1" (empty for none); the CSV's and the OMPL log's spelling.
std::string params_text(const ParamSetting& params);

}  // namespace uavplan
