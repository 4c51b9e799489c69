// OMPL's benchmark log format (the one ompl_benchmark_statistics.py reads into the database
// Planner Arena plots; grammar in OMPL's "The benchmark logfile format"): one experiment per
// scenario, one "planner" per planner and parameter setting, one measurement line per run.
#pragma once

#include <string>
#include <vector>

#include "uavplan/experiments/results.h"

namespace uavplan {

struct OmplLogHeader {
  std::string experiment;  // whitespace becomes '_'
  std::string host;
  std::string date;           // "Starting at" (the batch's start)
  std::string setup;          // multi-line text (the sweep and the scenario)
  double time_limit_s = 0.0;  // 0: none ("inf seconds per run")
  double memory_limit_mb = 0.0;
};

// The log of one scenario's runs. Run properties: time REAL (s), solved BOOLEAN, correct
// solution BOOLEAN (verified), solution length REAL (m), graph states INTEGER (expansions),
// seed INTEGER, violations INTEGER, flight time REAL (s), min separation REAL (m); a value
// that does not exist (no length without a plan) is left empty, as the format allows. "seconds
// spent to collect the data" is this experiment's: its runs' wall-clock times added up.
std::string ompl_log(const std::vector<RunRecord>& runs, const OmplLogHeader& header);

// The planner's name in the log: "astar" or "rrt[goal_bias=0.1,step_m=5]" (no whitespace).
std::string ompl_planner_name(const RunRecord& r);

}  // namespace uavplan
