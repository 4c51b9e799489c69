// MovingAI benchmark: ours against the textbook A* on a map and its scenario file.
// Usage: movingai MAP SCEN [astar|jps|jps+|jps-forward|theta] [LIMIT] [--no-reference]
// (--no-reference: our search alone, without the textbook A* beside it)
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "movingai_runner.h"

int main(int argc, char** argv) {
  if (argc < 3 || (argc > 5 && std::string(argv[5]) != "--no-reference")) {
    std::fprintf(stderr, "usage: %s MAP SCEN [astar|jps|jps+|jps-forward|theta] [LIMIT] [--no-reference]\n", argv[0]);
    return 2;
  }
  uavplan::bench::MovingAiOptions opt;
  if (argc > 3) opt.algorithm = argv[3];
  if (argc > 4) opt.limit = std::atoi(argv[4]);
  opt.reference = argc <= 5;
  try {
    const auto rep = uavplan::bench::run_movingai(argv[1], argv[2], opt);
    std::fputs(uavplan::bench::format_movingai(rep).c_str(), stdout);
    return rep.passed() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
