// P5 whole-mission tables. Usage: p5 [SCENARIO_DIR] (default: scenarios)
#include <cstdio>
#include <exception>

#include "p5_runner.h"

int main(int argc, char** argv) {
  try {
    bool ok = false;
    std::fputs(uavplan::bench::run_p5(argc > 1 ? argv[1] : "scenarios", &ok).c_str(), stdout);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
