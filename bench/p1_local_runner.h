// P1 Table 1: local replanning in the 40 m x 45 m window with moving obstacles. Our improved
// RRT and common RRT beside OMPL's RRT, RRTConnect and RRT* (fixed budget), all on the same
// problems with our World (plus the inflated discs) as the validity checker and exact segment
// checks; OMPL's paths get the improved RRT's own simplification (P1's pruning, then the
// shortcut), so only the planners differ.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uavplan::bench {

struct P1LocalOptions {
  int problems = 200;
  std::uint64_t seed = 1;
  double rrtstar_budget_ms = 25.0;  // RRT* improves until then
};

struct P1LocalRow {
  std::string planner;
  int problems = 0, solved = 0;
  double mean_ms = 0.0, median_ms = 0.0, p95_ms = 0.0;
  double mean_cost = 0.0;   // local route length (m), over the solved problems
  double mean_nodes = 0.0;  // tree nodes (ours; OMPL's vertices)
};

std::vector<P1LocalRow> run_p1_local(const P1LocalOptions& options);
std::string format_p1_local(const std::vector<P1LocalRow>& rows, const P1LocalOptions& options);
std::string p1_local_json(const std::vector<P1LocalRow>& rows);
// The targets: every problem solved by the improved RRT, its median time at most RRTConnect's,
// its mean cost below common RRT's and OMPL RRT's.
bool p1_local_targets_met(const std::vector<P1LocalRow>& rows);

}  // namespace uavplan::bench
