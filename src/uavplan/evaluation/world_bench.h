// World-query benchmark: random worlds of mixed obstacles; segment and point queries through
// the broad phase, timed and checked against brute force. Returns rows; printing is the
// caller's (bench/world_queries and `uavplan bench world`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uavplan {

struct WorldBenchRow {
  int obstacles = 0;
  int queries = 0;
  double segment_us = 0.0;        // broad phase + exact test, per segment query
  double segment_brute_us = 0.0;  // every obstacle, per segment query
  double point_us = 0.0;          // clearance query
  int collisions = 0;             // segment queries that collide
  int mismatches = 0;             // disagreements with brute force (must be 0)
};

std::vector<WorldBenchRow> run_world_bench(const std::vector<int>& obstacle_counts, int queries, std::uint64_t seed);

std::string format_world_bench(const std::vector<WorldBenchRow>& rows);

}  // namespace uavplan
