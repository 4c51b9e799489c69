// P2 benchmark: the paper's Table 1 (times to task 1, task 2 and the finish for 25 to 100 ants,
// ours beside the paper's), the colony's cost against the A* optimum on the same cell graph,
// and planning times.
#pragma once

#include <string>

namespace uavplan::bench {

std::string run_p2(const std::string& scenario_dir, bool* all_ok = nullptr);

}  // namespace uavplan::bench
