// P5 whole-mission benchmark (sec. 4.3, 4.2(b)): the phase timetable of p5_mission.yaml beside
// P5 Table 2, the minimum separation per phase, the largest turn of the route, the wall time of
// planning and simulating the whole mission; and the 45 -> 15 deg turn of a diamond of 4 (steady
// and minimum spacing beside P5's ~85 m and 70.5 m, safety distance 50 m).
#pragma once

#include <string>

namespace uavplan::bench {

std::string run_p5(const std::string& scenario_dir, bool* all_ok = nullptr);

}  // namespace uavplan::bench
