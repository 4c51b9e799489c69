#include "uavplan/planning/smoothing/waypoint_pruning.h"

#include <gtest/gtest.h>

#include "uavplan/core/units.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {
namespace {

const TimedSegmentCheck kFree = [](const Vec3&, double, const Vec3&) { return true; };

std::vector<Vec3> line(int n, double spacing) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(i * spacing, 0, 0);
  return pts;
}

TEST(WaypointPruning, P1DropsPointsWithinOneUavStepLookingFiveAhead) {
  // 1 m apart, UAV step 2.5 m: from each head the farthest point closer than 2.5 m is 2 ahead.
  const auto out = prune_within_step(line(11, 1.0), 2.5, 5, {}, kFree);
  ASSERT_EQ(out.size(), 6u);
  for (std::size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i], Vec3(2.0 * i, 0, 0));
  // The look-ahead caps the jump: with a 100 m step only 5 points are skipped at a time.
  EXPECT_EQ(prune_within_step(line(11, 1.0), 100.0, 5, {}, kFree).size(), 3u);
  // A barrier between the head and a candidate keeps the candidate's predecessor.
  const TimedSegmentCheck wall = [](const Vec3& a, double, const Vec3& b) { return !(a.x() < 1.5 && b.x() > 1.5); };
  const auto blocked = prune_within_step(line(5, 1.0), 2.5, 5, {}, wall);
  EXPECT_EQ(blocked[1], Vec3(1, 0, 0));
}

TEST(WaypointPruning, ShortcutKeepsTheTurnLimitAtBothEnds) {
  // Around a corner: a route east then north; a straight jump would turn 45 degrees at the start.
  const std::vector<Vec3> pts{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}};
  EXPECT_EQ(shortcut_within_limits(pts, {}, kFree).size(), 2u);
  PruneLimits limits;
  limits.start_direction = Vec3(1, 0, 0);
  limits.max_turn_rad = deg_to_rad(30);
  EXPECT_EQ(shortcut_within_limits(pts, limits, kFree), pts);
  limits.max_turn_rad = deg_to_rad(50);
  limits.end_direction = Vec3(-1, 0, 0);  // going on west: a 135 degree turn at the end
  EXPECT_EQ(shortcut_within_limits(pts, limits, kFree), pts);
}

TEST(WaypointPruning, TimedChecksHoldForTheRestOfTheRoute) {
  // Reaching x >= 8 is refused before 5 m of flight (a keep-out still there). Flown as given the
  // UAV is 5.66 m along at (4, 0); cutting the detour brings it there after 4 m, so the next
  // segment would be too early: the jump is refused and every segment holds at its new time.
  const std::vector<Vec3> pts{{0, 0, 0}, {2, 2, 0}, {4, 0, 0}, {8, 0, 0}, {12, 0, 0}};
  const TimedSegmentCheck early = [](const Vec3&, double along, const Vec3& b) { return !(b.x() >= 8 && along < 5.0); };
  PruneLimits limits;
  limits.timed = true;
  for (const auto& out : {shortcut_within_limits(pts, limits, early), prune_within_step(pts, 5.0, 5, limits, early)}) {
    double along = 0.0;
    for (std::size_t i = 1; i < out.size(); ++i) {
      EXPECT_TRUE(early(out[i - 1], along, out[i])) << i;
      along += (out[i] - out[i - 1]).norm();
    }
    EXPECT_EQ(out.back(), pts.back());
  }
}

}  // namespace
}  // namespace uavplan
