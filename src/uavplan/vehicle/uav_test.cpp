#include "uavplan/vehicle/uav.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace uavplan {
namespace {

TEST(Uav, PitchOfSegments) {
  EXPECT_NEAR(pitch_rad(Vec3(1, 0, 1)), kPi / 4, 1e-12);
  EXPECT_NEAR(pitch_rad(Vec3(0, 0, -3)), -kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(pitch_rad(Vec3(0, 0, 0)), 0.0);
}

TEST(Uav, TurnIsTheLargerOfThreeDAngleAndYawChange) {
  EXPECT_NEAR(turn_rad(Vec3(1, 0, 0), Vec3(0, 1, 0)), kPi / 2, 1e-12);
  // Climbing legs 90 degrees apart in yaw meet at 60 degrees in 3-D: the yaw change counts.
  EXPECT_NEAR(turn_rad(Vec3(1, 0, 1), Vec3(0, 1, 1)), kPi / 2, 1e-12);
  // Same yaw, pitch change only: the 3-D angle counts.
  EXPECT_NEAR(turn_rad(Vec3(1, 0, 0), Vec3(1, 0, 1)), kPi / 4, 1e-12);
  // A vertical segment has no yaw.
  EXPECT_NEAR(turn_rad(Vec3(1, 0, 0), Vec3(0, 0, 1)), kPi / 2, 1e-12);
}

// The planners' check without trigonometry agrees with turn_rad on both sides of the limit.
TEST(Uav, TurnWithinAgreesWithTurnRad) {
  std::uint64_t state = 12345;
  auto uniform = [&] {  // a small LCG: the test needs no distribution, only spread
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53 * 2.0 - 1.0;
  };
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 a(uniform(), uniform(), 0.3 * uniform()),
        b(uniform(), uniform(), k % 5 == 0 ? 3.0 * uniform() : 0.3 * uniform());
    const double limit = 0.05 + 1.5 * (0.5 + 0.5 * uniform());
    const double turn = turn_rad(a, b);
    if (std::abs(turn - limit) < 1e-9) continue;  // rounding decides there
    EXPECT_EQ(turn_within(a, b, limit), turn <= limit) << k;
    ++checked;
  }
  EXPECT_GT(checked, 19000);
  EXPECT_TRUE(turn_within(Vec3(1, 0, 1), Vec3(0, 1, 1), kPi / 2 + 1e-9));  // the yaw change counts
  EXPECT_FALSE(turn_within(Vec3(1, 0, 1), Vec3(0, 1, 1), kPi / 2 - 1e-3));
  EXPECT_TRUE(turn_within(Vec3(1, 0, 0), Vec3(0, 0, 0), 0.0));  // no segment, no turn
}

TEST(Uav, RouteLimitsIncludeTheStartHeading) {
  UavSpec u;
  u.max_turn_rad = deg_to_rad(60);
  u.max_climb_rad = deg_to_rad(30);
  const std::vector<Vec3> pts{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {20, 10, 10}};
  auto v = check_route_limits(pts, u);
  // 90 deg turn at waypoint 1, 45 deg climb on segment 2 (whose turn is 90 deg too).
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].kind, LimitViolation::Kind::turn);
  EXPECT_EQ(v[0].index, 1u);
  u.heading_rad = deg_to_rad(180);
  v = check_route_limits(pts, u);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0].kind, LimitViolation::Kind::turn);
  EXPECT_EQ(v[0].index, 0u);
}

TEST(Uav, ZeroLengthSegmentsAreSkipped) {
  UavSpec u;
  u.max_turn_rad = deg_to_rad(10);
  const std::vector<Vec3> pts{{0, 0, 0}, {10, 0, 0}, {10, 0, 0}, {20, 0, 0}};
  EXPECT_TRUE(check_route_limits(pts, u).empty());
}

}  // namespace
}  // namespace uavplan
