// P1 benchmark tables (whole mission). Usage: p1 [SCENARIO_DIR] [RUNS] (default: scenarios 20)
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "p1_runner.h"

int main(int argc, char** argv) {
  try {
    bool ok = false;
    std::fputs(
        uavplan::bench::run_p1(argc > 1 ? argv[1] : "scenarios", argc > 2 ? std::atoi(argv[2]) : 20, &ok).c_str(),
        stdout);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
