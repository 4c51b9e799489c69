// libMultiRobotPlanning's grid MAPF benchmark, like for like: every instance file of a folder
// solved as 4-connected grid MAPF with waits (vertex and swap conflicts, sum of costs), each
// solution checked by our own validator before it counts; per agent count: solved within the
// limit, median and worst time, sum of costs against the best bound known, beside the
// reference's figures measured on this machine.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "uavplan/coordination/spacetime/mapf.h"

namespace uavplan::bench {

struct MapfBenchOptions {
  MapfOptions solver;            // method, w, orders (its stop is set per instance)
  double time_limit_s = 30.0;    // per instance
  double optimal_limit_s = 0.0;  // > 0: CBS per instance within this, for the optimum where it finishes
  int limit = 0;                 // > 0: this many instances per agent count, spread evenly
  std::string out_dir;           // non-empty: one solution file per instance, named after it
};

struct MapfRun {
  std::string file;
  int agents = 0;
  bool solved = false;
  std::string invalid;  // the validator's objection to a claimed solution
  double ms = 0.0;
  int sum_of_costs = 0, lower_bound = 0;
  int optimum = -1;  // CBS's, where it finished within optimal_limit_s
  std::string method;
  double ratio() const;  // sum of costs over the optimum, else over the lower bound
};

struct MapfBenchReport {
  std::vector<MapfRun> runs;
  MapfBenchOptions options;
  bool passed() const;  // every instance solved and valid
};

// Reads every *.yaml instance of `dir` first (InputError on a bad one: nothing is solved or
// written), then solves them by agent count; `progress(done, total)` after each.
MapfBenchReport run_mapf_bench(const std::string& dir, const MapfBenchOptions& options,
                               const std::function<void(std::size_t, std::size_t)>& progress = {});
std::string format_mapf_bench(const MapfBenchReport& report);

}  // namespace uavplan::bench
