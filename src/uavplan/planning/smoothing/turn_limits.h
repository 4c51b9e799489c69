// Reshapes a route so that every turn between consecutive segments stays within the UAV's
// limit, including the first segment against the start heading.
//  - An unpinned corner is replaced by a fillet: the inscribed polygon of a circular arc
//    tangent to both legs, with enough chords that each vertex turns at most the limit.
//  - At the start (against the heading), at a pinned point (a via point the route must touch),
//    or where no fillet fits, the route flies over the point and pursues the next one, turning
//    at most the limit per chord, climbing at most the climb limit (a helix when it must).
//    Where that pursuit swings wide into an obstacle, it pursues a point of the leg nearer the
//    corner instead (half the leg, a quarter, ...: a tighter turn) and flies the leg on from it.
// Every new segment is checked with `ok`; nothing unchecked is ever emitted.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "uavplan/core/status.h"
#include "uavplan/planning/planner.h"
#include "uavplan/planning/smoothing/shortcut.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {

struct TurnLimits {
  double max_turn_rad;
  double max_climb_rad;
};

// solved, or failed for no_route (no room to turn within the limit at a corner).
struct TurnShaping : Outcome {
  std::vector<Vec3> waypoints;
};

TurnShaping enforce_turn_limits(std::span<const Vec3> points, std::span<const char> pinned,
                                std::optional<double> start_heading_rad, const TurnLimits& limits,
                                const SegmentPredicate& ok);

// The same for a UAV's limits and start heading; the points unchanged when it has neither.
TurnShaping shape_turns(std::span<const Vec3> points, std::span<const char> pinned, const UavSpec& uav,
                        const SegmentPredicate& ok);

// A planner's last step: its route through the points with the corners shaped by shape_turns,
// `res` solved with it, or left failed with "turn limits: ..." when they cannot be.
void finish_with_turns(std::span<const Vec3> points, std::span<const char> pinned, const UavSpec& uav,
                       const SegmentPredicate& ok, PlanResult& res);

}  // namespace uavplan
