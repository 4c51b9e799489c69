#include "uavplan/vehicle/uav.h"

#include <gtest/gtest.h>

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
