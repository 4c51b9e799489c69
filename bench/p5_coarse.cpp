// P5 coarse-planning tables. Usage: p5_coarse [SCENARIO_DIR] [WORLDS] (default: scenarios 100)
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "p5_coarse_runner.h"

int main(int argc, char** argv) {
  try {
    bool ok = false;
    std::fputs(uavplan::bench::run_p5_coarse(argc > 1 ? argv[1] : "scenarios", argc > 2 ? std::atoi(argv[2]) : 100, &ok)
                   .c_str(),
               stdout);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
