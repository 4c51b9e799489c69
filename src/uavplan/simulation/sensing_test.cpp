#include "uavplan/simulation/sensing.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

TEST(Eq7, GroundVelocityFromTwoRelativeObservations) {
  // The UAV flies east at 5 m/s; a still obstacle ahead: relative positions shrink by 5 m a second.
  const Vec3 own0(0, 0, 0), own1(5, 0, 0), still(30, 10, 0);
  EXPECT_EQ(ground_velocity(still - own0, still - own1, own0, own1, 1.0), Vec3::Zero());
  // The paper's printed sign (rel change minus own displacement) would make it move at 10 m/s.
  EXPECT_EQ(((still - own1) - (still - own0) - (own1 - own0)).norm(), 10.0);
  // A moving one: exactly its velocity, whatever the UAV does.
  const Vec3 v(-2, 3, 0.5), o0(40, -5, 2), o1 = o0 + 2.0 * v, u1(3, 7, 1);
  EXPECT_TRUE(ground_velocity(o0 - own0, o1 - u1, own0, u1, 2.0).isApprox(v, 1e-12));
}

std::vector<ObjectState> truth(const Vec3& obstacle, const Vec3& other_uav) {
  return {{"m1", 2.0, false, obstacle}, {"u1", 0.5, true, Vec3::Zero()}, {"u2", 0.5, true, other_uav}};
}

TEST(Sensor, SeesWithinRangeOfTheSurfaceOnlyAndEstimatesFromTwoLooks) {
  Sensor s;
  s.range_m = 20.0;
  // The obstacle's surface 21 m away: not seen; the other UAV 10 m away: seen, first time.
  sense(s, truth(Vec3(23, 0, 0), Vec3(0, 10, 0)), 1, Vec3::Zero(), 0.0);
  ASSERT_EQ(s.tracks.size(), 1u);
  EXPECT_EQ(s.tracks[0].id, "u2");
  EXPECT_TRUE(s.tracks[0].is_uav);
  EXPECT_FALSE(s.tracks[0].velocity_mps);
  // One second later (the UAV moved 5 m east): the obstacle came 4 m closer (seen, new), the other
  // UAV moved 3 m north (velocity from the two looks).
  sense(s, truth(Vec3(19, 0, 0), Vec3(0, 13, 0)), 1, Vec3(5, 0, 0), 1.0);
  ASSERT_EQ(s.tracks.size(), 2u);
  EXPECT_EQ(s.tracks[0].id, "m1");
  EXPECT_FALSE(s.tracks[0].velocity_mps);
  EXPECT_EQ(s.tracks[0].position(), Vec3(19, 0, 0));
  // It was out of range a second ago (more than 22 m from where the UAV was), so it came at
  // least 22 - 19 = 3 m in that second.
  EXPECT_NEAR(s.tracks[0].entered_speed_mps, 3.0, 1e-12);
  ASSERT_TRUE(s.tracks[1].velocity_mps);
  EXPECT_TRUE(s.tracks[1].velocity_mps->isApprox(Vec3(0, 3, 0), 1e-12));
  // The other UAV leaves the range and comes back: its velocity comes from the last look before.
  sense(s, truth(Vec3(19, 0, 0), Vec3(0, 40, 0)), 1, Vec3(5, 0, 0), 2.0);
  EXPECT_EQ(s.tracks.size(), 1u);
  ASSERT_EQ(s.lost.size(), 1u);
  sense(s, truth(Vec3(19, 0, 0), Vec3(0, 19, 0)), 1, Vec3(5, 0, 0), 3.0);
  ASSERT_EQ(s.tracks.size(), 2u);
  EXPECT_TRUE(s.tracks[1].velocity_mps->isApprox(Vec3(0, 3, 0), 1e-12));
  EXPECT_TRUE(s.lost.empty());
}

}  // namespace
}  // namespace uavplan
