#include "uavplan/planning/smoothing/waypoint_pruning.h"

#include "uavplan/vehicle/uav.h"

namespace uavplan {
namespace {

// Greedy jumps: from the head, the farthest candidate j (searched from `last(head)` down) that
// `admissible` accepts, falling back to the next point.
// Whether pts[j..] still holds when the UAV reaches pts[j] having flown along_m.
bool rest_holds(std::span<const Vec3> pts, std::size_t j, double along_m, const TimedSegmentCheck& ok) {
  for (std::size_t k = j; k + 1 < pts.size(); ++k) {
    if (!ok(pts[k], along_m, pts[k + 1])) return false;
    along_m += (pts[k + 1] - pts[k]).norm();
  }
  return true;
}

template <class Last, class Admissible>
std::vector<Vec3> jump(std::span<const Vec3> pts, const PruneLimits& limits, const TimedSegmentCheck& ok, Last&& last,
                       Admissible&& admissible) {
  std::vector<Vec3> out;
  if (pts.empty()) return out;
  out.push_back(pts[0]);
  std::optional<Vec3> in = limits.start_direction;
  const bool turns = limits.max_turn_rad < kPi;  // any turn is allowed otherwise
  double along = 0.0;
  std::size_t head = 0;
  while (head + 1 < pts.size()) {
    std::size_t next = head + 1;
    for (std::size_t j = last(head); j > head + 1; --j) {
      const Vec3 seg = pts[j] - pts[head];
      if (turns && in && turn_rad(*in, seg) > limits.max_turn_rad + kAngleTolerance_rad) continue;
      const std::optional<Vec3> on =
          j + 1 < pts.size() ? std::optional<Vec3>(pts[j + 1] - pts[j]) : limits.end_direction;
      if (turns && on && turn_rad(seg, *on) > limits.max_turn_rad + kAngleTolerance_rad) continue;
      if (!admissible(head, j, along)) continue;
      if (limits.timed && !rest_holds(pts, j, along + seg.norm(), ok)) continue;
      next = j;
      break;
    }
    const Vec3 seg = pts[next] - pts[head];
    along += seg.norm();
    if (seg.norm() > 0.0) in = seg;
    out.push_back(pts[next]);
    head = next;
  }
  return out;
}

}  // namespace

std::vector<Vec3> prune_within_step(std::span<const Vec3> pts, double step_m, int lookahead, const PruneLimits& limits,
                                    const TimedSegmentCheck& ok) {
  const auto last = [&](std::size_t head) {
    return std::min(pts.size() - 1, head + static_cast<std::size_t>(std::max(1, lookahead)));
  };
  return jump(pts, limits, ok, last, [&](std::size_t head, std::size_t j, double along) {
    return (pts[j] - pts[head]).norm() < step_m && ok(pts[head], along, pts[j]);
  });
}

std::vector<Vec3> shortcut_within_limits(std::span<const Vec3> pts, const PruneLimits& limits,
                                         const TimedSegmentCheck& ok) {
  const auto last = [&](std::size_t) { return pts.size() - 1; };
  return jump(pts, limits, ok, last,
              [&](std::size_t head, std::size_t j, double along) { return ok(pts[head], along, pts[j]); });
}

}  // namespace uavplan
