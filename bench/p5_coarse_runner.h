// P5 coarse-planning benchmark: sec. 4.1 (multi-step PSO against the single-step baseline and
// grid A* on p5_coarse.yaml: the largest turn between segments, cylinder intrusion, lengths,
// times), sec. 4.2(a) (entry headings 0, 180 and -45 deg into one task point, route and flown),
// the planning time per waypoint and per 1000 km, and random large worlds (100-1000 km, 5-20
// cylinders, random entry headings) checked by the verifier.
#pragma once

#include <string>

namespace uavplan::bench {

std::string run_p5_coarse(const std::string& scenario_dir, int worlds, bool* all_ok = nullptr);

}  // namespace uavplan::bench
