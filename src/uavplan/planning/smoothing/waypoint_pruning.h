// Redundant-waypoint removal for sampled routes (P1 sec. 2.3), with checks that may depend on
// when a segment is flown: the route is flown at constant speed, so the length flown before a
// point fixes its time. Both keep the first and last points, the turn limit at every kept
// waypoint (against `start_direction` at the first) and never emit a segment `ok` refuses.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

// ok(a, along_m, b): may the UAV fly straight from a to b, having flown along_m before a?
using TimedSegmentCheck = std::function<bool(const Vec3& a, double along_m, const Vec3& b)>;

struct PruneLimits {
  std::optional<Vec3> start_direction;  // the direction flown into the first point, if any
  std::optional<Vec3> end_direction;    // the direction flown on from the last point, if any
  double max_turn_rad = 3.141592653589793;
  // `ok` depends on the time: a jump makes every later point earlier, so it is taken only when
  // the rest of the route still holds at its new times.
  bool timed = false;
};

// P1's pruning as printed ("For i = 5:1 ... If juli(S0, Si) < step and no barrier"): from the
// head S0 look at most `lookahead` waypoints ahead, jump to the farthest S_i closer than
// `step_m` (one UAV step) that S0 sees, drop the ones between; repeat from the new head.
std::vector<Vec3> prune_within_step(std::span<const Vec3> points, double step_m, int lookahead,
                                    const PruneLimits& limits, const TimedSegmentCheck& ok);

// Line-of-sight shortcut: from each kept point jump to the farthest later point it may fly to
// straight, turning within the limit there and leaving that point along its old next segment
// within the limit too (so a continuation always exists).
std::vector<Vec3> shortcut_within_limits(std::span<const Vec3> points, const PruneLimits& limits,
                                         const TimedSegmentCheck& ok);

}  // namespace uavplan
