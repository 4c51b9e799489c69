// P3 benchmark: Tables 3 and 4 (per-UAV path scores before and after smoothing, ours beside the
// paper's) for the improved and the traditional field, and a scaling table for 9 to 400 UAVs in
// random obstacle fields.
#pragma once

#include <string>

namespace uavplan::bench {

std::string run_p3(const std::string& scenario_dir, bool* all_ok = nullptr);

}  // namespace uavplan::bench
