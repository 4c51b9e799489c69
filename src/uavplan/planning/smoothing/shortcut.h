// Redundant-waypoint removal: greedy line-of-sight shortcutting with an exact segment check.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

using SegmentPredicate = std::function<bool(const Vec3&, const Vec3&)>;

// Keeps the first and last points and every `pinned` one; from each kept point jumps to the
// farthest later point it may fly to straight (`ok`), never past a pinned point. The result is
// never longer than the input (triangle inequality) and every new segment satisfies `ok`.
std::vector<Vec3> shortcut(std::span<const Vec3> points, std::span<const char> pinned, const SegmentPredicate& ok);

}  // namespace uavplan
