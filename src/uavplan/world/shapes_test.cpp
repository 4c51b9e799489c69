#include "uavplan/world/shapes.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

std::vector<Obstacle> sample_shapes() {
  return {Sphere{Vec3(0, 0, 0), 2.0}, Cylinder{Vec2(1, 1), 1.5, -1.0, 2.0}, Box{Vec3(-1, -2, -1), Vec3(2, 1, 0.5)},
          Prism{{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, -1.0, 1.0}};  // non-convex L
}

// Oracle for point distance: inside tests by definition, distance by dense sampling of the
// solid's surface is costly; instead check two properties that pin it down: 0 inside, and
// 1-Lipschitz with a zero at the nearest surface point.
TEST(Shapes, PointDistanceKnownValues) {
  EXPECT_DOUBLE_EQ(point_distance(Sphere{Vec3(0, 0, 0), 2.0}, Vec3(5, 0, 0)), 3.0);
  EXPECT_DOUBLE_EQ(point_distance(Sphere{Vec3(0, 0, 0), 2.0}, Vec3(1, 0, 0)), 0.0);
  EXPECT_DOUBLE_EQ(point_distance(Cylinder{Vec2(0, 0), 1.0, 0.0, 10.0}, Vec3(4, 0, 5)), 3.0);
  EXPECT_DOUBLE_EQ(point_distance(Cylinder{Vec2(0, 0), 1.0, 0.0, 10.0}, Vec3(4, 0, 14)), 5.0);
  EXPECT_DOUBLE_EQ(point_distance(Box{Vec3(0, 0, 0), Vec3(1, 1, 1)}, Vec3(2, 2, 0.5)), std::sqrt(2.0));
  const Prism l{{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, 0.0, 1.0};
  EXPECT_DOUBLE_EQ(point_distance(l, Vec3(3, 3, 0.5)), 2.0);  // in the notch: to the inner edge y = 1
  EXPECT_DOUBLE_EQ(point_distance(l, Vec3(0.5, 3, 0.5)), 0.0);
  EXPECT_DOUBLE_EQ(point_distance(l, Vec3(0.5, 3, 4.0)), 3.0);
}

TEST(Shapes, BoundingBoxesContainTheSolid) {
  Rng r(1);
  for (const auto& o : sample_shapes()) {
    const Aabb box = bounding_box(o);
    for (int k = 0; k < 2000; ++k) {
      const Vec3 p(r.uniform(-6, 6), r.uniform(-6, 6), r.uniform(-6, 6));
      if (point_distance(o, p) == 0.0) {
        ASSERT_TRUE(box.contains(p));
      }
    }
  }
}

// Segment distance against the brute-force oracle: the minimum of the point distance over
// 4001 samples along the segment. Exact <= sampled, and close to it.
TEST(Shapes, SegmentDistanceAgainstSampling) {
  Rng r(2);
  for (const auto& o : sample_shapes()) {
    for (int k = 0; k < 300; ++k) {
      const Vec3 a(r.uniform(-7, 7), r.uniform(-7, 7), r.uniform(-5, 5));
      const Vec3 b(r.uniform(-7, 7), r.uniform(-7, 7), r.uniform(-5, 5));
      double sampled = 1e300;
      for (int i = 0; i <= 4000; ++i) sampled = std::min(sampled, point_distance(o, a + (b - a) * (i / 4000.0)));
      const double exact = segment_distance(o, a, b);
      ASSERT_LE(exact, sampled + 1e-9) << "shape " << o.index() << " case " << k;
      ASSERT_NEAR(exact, sampled, (b - a).norm() / 4000.0 + 1e-9) << "shape " << o.index() << " case " << k;
    }
  }
}

// With a cap, the answer is the exact distance below the cap and a lower bound of it at or
// above the cap (what the world's queries need to keep the nearer of two).
TEST(Shapes, SegmentDistanceWithACapIsExactBelowItAndABoundAbove) {
  Rng r(3);
  for (const auto& o : sample_shapes()) {
    for (int k = 0; k < 2000; ++k) {
      const Vec3 a(r.uniform(-9, 9), r.uniform(-9, 9), r.uniform(-7, 7));
      const Vec3 b(r.uniform(-9, 9), r.uniform(-9, 9), r.uniform(-7, 7));
      const double cap = r.uniform(0.0, 4.0), exact = segment_distance(o, a, b),
                   capped = segment_distance(o, a, b, cap);
      if (exact < cap) {
        ASSERT_NEAR(capped, exact, 1e-9) << "shape " << o.index() << " case " << k;
      } else {
        ASSERT_GE(capped, cap) << "shape " << o.index() << " case " << k;
        ASSERT_LE(capped, exact + 1e-12) << "shape " << o.index() << " case " << k;
      }
    }
  }
}

TEST(Shapes, ClosestPointIsOnTheSolidAtThePointDistance) {
  Rng r(3);
  for (const auto& o : sample_shapes())
    for (int k = 0; k < 500; ++k) {
      const Vec3 p(r.uniform(-7, 7), r.uniform(-7, 7), r.uniform(-5, 5));
      const Vec3 c = closest_point(o, p);
      ASSERT_NEAR(point_distance(o, c), 0.0, 1e-9);
      ASSERT_NEAR((c - p).norm(), point_distance(o, p), 1e-9) << "shape " << o.index();
    }
}

TEST(Shapes, SegmentThroughNonConvexNotchDoesNotCollide) {
  const Prism l{{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, 0.0, 1.0};
  // Inside the empty notch of the L: 1 m from both inner edges at its first end.
  EXPECT_NEAR(segment_distance(l, Vec3(2, 2, 0.5), Vec3(3.5, 3.5, 0.5)), 1.0, 1e-12);
  // Through both arms.
  EXPECT_DOUBLE_EQ(segment_distance(l, Vec3(0.5, 5, 0.5), Vec3(0.5, -1, 0.5)), 0.0);
  // Above the roof.
  EXPECT_DOUBLE_EQ(segment_distance(l, Vec3(0.5, 5, 3.0), Vec3(0.5, -1, 3.0)), 2.0);
}

}  // namespace
}  // namespace uavplan
