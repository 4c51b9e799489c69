// P1 Table 1 (local replanning). Usage: p1_local [PROBLEMS] [SEED]
#include <cstdio>
#include <cstdlib>

#include "p1_local_runner.h"

int main(int argc, char** argv) {
  uavplan::bench::P1LocalOptions opt;
  if (argc > 1) opt.problems = std::atoi(argv[1]);
  if (argc > 2) opt.seed = std::strtoull(argv[2], nullptr, 10);
  const auto rows = uavplan::bench::run_p1_local(opt);
  std::fputs(uavplan::bench::format_p1_local(rows, opt).c_str(), stdout);
  return uavplan::bench::p1_local_targets_met(rows) ? 0 : 1;
}
