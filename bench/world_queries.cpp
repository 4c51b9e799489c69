// World-query benchmark: segment collision and clearance queries through the BVH broad phase
// against brute force, on random worlds of 100 to 10,000 mixed obstacles.
// Usage: world_queries [QUERIES] [SEED]
#include <cstdio>
#include <cstdlib>

#include "uavplan/evaluation/world_bench.h"

int main(int argc, char** argv) {
  const int queries = argc > 1 ? std::atoi(argv[1]) : 2000;
  const unsigned long long seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 7;
  const auto rows = uavplan::run_world_bench({100, 1000, 10000}, queries, seed);
  std::fputs(uavplan::format_world_bench(rows).c_str(), stdout);
  for (const auto& r : rows)
    if (r.mismatches) return 1;
  return 0;
}
