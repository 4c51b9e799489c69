// P1 benchmark (whole mission): the global route on p1_formation (ETA, cost, colony time, colony
// against the Dijkstra optimum on the same roadmap), the colony on random threat fields, and
// Table 2: 20 seeded runs of the whole formation mission with the improved RRT locally (A-RRT)
// beside the same mission with common RRT locally, and common RRT for everything, each beside
// the paper's numbers, with the formation's metrics.
#pragma once

#include <string>

namespace uavplan::bench {

std::string run_p1(const std::string& scenario_dir, int runs, bool* all_ok = nullptr);

}  // namespace uavplan::bench
