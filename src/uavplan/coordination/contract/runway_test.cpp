#include "uavplan/coordination/contract/runway.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

// A 1000 m runway heading north from (100, 0, 20).
Airfield north_runway() {
  Airfield af;
  af.position = Vec3(100, 0, 20);
  af.runway_heading_rad = kPi / 2;
  af.runway_length_m = 1000.0;
  return af;
}

TEST(Runway, TheBoxIsTheLengthThirtyMetresEitherSideAndTenMetresUp) {
  const Airfield af = north_runway();
  EXPECT_TRUE(on_runway(af, Vec3(100, 0, 20)));
  EXPECT_TRUE(on_runway(af, Vec3(129, 999, 29)));
  EXPECT_FALSE(on_runway(af, Vec3(131, 500, 20)));  // beside it
  EXPECT_FALSE(on_runway(af, Vec3(100, 500, 31)));  // above it
  EXPECT_FALSE(on_runway(af, Vec3(100, -1, 20)));   // before the threshold
  EXPECT_FALSE(on_runway(af, Vec3(100, 1001, 20)));
}

TEST(Runway, OccupancyRunsFromLiningUpToClimbingOutExactly) {
  const Airfield af = north_runway();
  // Taxi from 100 m east onto the threshold (enters the box 30 m out: t = 7), roll 500 m, climb
  // at 10 % to 30 m above (above the box at 100 m of climb: t = 20 + 10 = 30).
  const Trajectory tr = {{0, Vec3(200, 0, 20)},
                         {10, Vec3(100, 0, 20)},
                         {20, Vec3(100, 500, 20)},
                         {40, Vec3(100, 700, 40)},
                         {60, Vec3(100, 2000, 200)}};
  const std::vector<TimeSpan> occ = runway_occupancy(af, tr);
  ASSERT_EQ(occ.size(), 1u);
  EXPECT_NEAR(occ[0].from_s, 7.0, 1e-9);
  EXPECT_NEAR(occ[0].to_s, 30.0, 1e-9);
}

TEST(Runway, ALandingOccupiesItFromTouchdownToItsLastRow) {
  const Airfield af = north_runway();
  // Glide from 50 m up 500 m before the threshold, 10 m up at t = 40 over along 0 ... stop.
  const Trajectory tr = {
      {0, Vec3(100, -500, 70)}, {50, Vec3(100, 0, 30)}, {60, Vec3(100, 100, 20)}, {80, Vec3(100, 400, 20)}};
  const std::vector<TimeSpan> occ = runway_occupancy(af, tr);
  ASSERT_EQ(occ.size(), 1u);
  EXPECT_NEAR(occ[0].from_s, 50.0, 1e-9);
  EXPECT_NEAR(occ[0].to_s, 80.0, 1e-9);
  EXPECT_TRUE(runway_occupancy(af, {{0, Vec3(500, 0, 20)}, {10, Vec3(500, 500, 20)}}).empty());
}

TEST(Runway, TwoUavsOverlapOnlyWhenTheyShareTime) {
  const std::vector<TimeSpan> a = {{0, 10}, {100, 130}}, b = {{10, 20}, {125, 140}};
  const auto o = runway_overlap(a, b);
  ASSERT_TRUE(o);
  EXPECT_DOUBLE_EQ(o->from_s, 125.0);
  EXPECT_DOUBLE_EQ(o->to_s, 130.0);
  EXPECT_FALSE(runway_overlap({{0, 10}}, {{10, 20}}));  // one leaves as the other lines up
  EXPECT_FALSE(runway_overlap({}, b));
}

}  // namespace
}  // namespace uavplan
