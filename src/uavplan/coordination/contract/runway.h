// formation_mission's runway (contract): from the threshold `runway_length_m` along its heading,
// kRunwayHalfWidth_m either side of the centreline, up to kAirborneAbove_m above the airfield.
// A UAV occupies it while it is inside that box: from lining up to the end of its take-off roll
// (until it climbs above the box or leaves its end) and from touchdown to the end of its roll-out
// (its last row, after which it has taxied off). The runway holds one UAV at a time.
#pragma once

#include <optional>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

inline constexpr double kRunwayHalfWidth_m = 30.0;
// Occupancies that share less than this (one leaves as the other enters) do not overlap.
inline constexpr double kRunwayOverlap_s = 1e-6;

struct TimeSpan {
  double from_s = 0.0, to_s = 0.0;
};

bool on_runway(const Airfield& airfield, const Vec3& p);

// When the UAV flying `trajectory` is on the runway, exactly (its rows joined by straight
// lines), in time order; spans that meet are one.
std::vector<TimeSpan> runway_occupancy(const Airfield& airfield, const Trajectory& trajectory);

// The first time two UAVs are on the runway together (and until when), if ever.
std::optional<TimeSpan> runway_overlap(const std::vector<TimeSpan>& a, const std::vector<TimeSpan>& b);

}  // namespace uavplan
