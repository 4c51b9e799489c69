#include "uavplan/core/geometry.h"
#include "uavplan/core/units.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// Brute force: the smallest distance over a dense grid of parameter pairs.
double sampled_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  double best = 1e300;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j)
      best = std::min(best, ((p0 + (p1 - p0) * i / 200.0) - (q0 + (q1 - q0) * j / 200.0)).norm());
  return best;
}

TEST(Geometry, SegmentSegmentDistanceAgainstSampling) {
  Rng r(3);
  for (int k = 0; k < 50; ++k) {
    const Vec3 p0(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5));
    const Vec3 p1(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5));
    const Vec3 q0(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5));
    const Vec3 q1 = k % 5 == 0 ? q0 + 2.0 * (p1 - p0) : Vec3(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5));
    const double exact = segment_segment_distance(p0, p1, q0, q1);
    const double sampled = sampled_segment_distance(p0, p1, q0, q1);
    EXPECT_LE(exact, sampled + 1e-9);
    EXPECT_NEAR(exact, sampled, 0.1);
  }
}

TEST(Geometry, PointSegmentDistance) {
  double t = -1;
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(1, 0, 0), &t), 1.0);
  EXPECT_DOUBLE_EQ(t, 0.5);
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec3(3, 0, 0), Vec3(-1, 0, 0), Vec3(1, 0, 0)), 2.0);
}

TEST(Geometry, PointInNonConvexPolygon) {
  const std::vector<Vec2> l{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  EXPECT_TRUE(point_in_polygon(Vec2(0.5, 3), l));
  EXPECT_TRUE(point_in_polygon(Vec2(3, 0.5), l));
  EXPECT_FALSE(point_in_polygon(Vec2(3, 3), l));
  EXPECT_FALSE(point_in_polygon(Vec2(-1, 0.5), l));
  EXPECT_NEAR(point_polygon_boundary_distance(Vec2(3, 3), l), 2.0, 1e-12);  // to the inner edge y = 1
  EXPECT_DOUBLE_EQ(polygon_signed_area(l), 7.0);
}

TEST(Geometry, SegmentIntersection2d) {
  EXPECT_TRUE(segments_intersect_2d({0, 0}, {2, 2}, {0, 2}, {2, 0}));
  EXPECT_FALSE(segments_intersect_2d({0, 0}, {1, 1}, {0, 2}, {2, 3}));
  EXPECT_TRUE(segments_intersect_2d({0, 0}, {2, 0}, {1, 0}, {1, 5}));  // touching
}

TEST(Geometry, ClipSegmentToBox) {
  double t0, t1;
  const Aabb box{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  ASSERT_TRUE(clip_segment_to_box(Vec3(-1, 0.5, 0.5), Vec3(3, 0.5, 0.5), box, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 0.25);
  EXPECT_DOUBLE_EQ(t1, 0.5);
  EXPECT_FALSE(clip_segment_to_box(Vec3(-1, 2, 0.5), Vec3(3, 2, 0.5), box, t0, t1));
}

TEST(Geometry, GoldenSectionFindsConvexMinimum) {
  EXPECT_NEAR(golden_section_min([](double t) { return (t - 0.3) * (t - 0.3) + 2.0; }, 0.0, 1.0), 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(golden_section_min([](double t) { return std::max(0.0, std::abs(t - 0.5) - 0.1); }, 0.0, 1.0), 0.0);
}

TEST(Geometry, PolygonSelfIntersection) {
  const std::vector<Vec2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_FALSE(polygon_self_intersection(square));
  EXPECT_FALSE(polygon_self_intersection(std::vector<Vec2>(square.rbegin(), square.rend())));  // clockwise
  const std::vector<Vec2> ell{{0, 0}, {20, 0}, {20, 5}, {5, 5}, {5, 20}, {0, 20}};             // concave
  EXPECT_FALSE(polygon_self_intersection(ell));
  const auto bowtie = polygon_self_intersection(std::vector<Vec2>{{200, 200}, {260, 260}, {260, 200}, {200, 262}});
  ASSERT_TRUE(bowtie);
  EXPECT_EQ(*bowtie, std::make_pair(std::size_t{0}, std::size_t{2}));
  const auto spike =
      polygon_self_intersection(std::vector<Vec2>{{0, 0}, {10, 0}, {10, 10}, {10, 20}, {10, 5}, {0, 10}});
  ASSERT_TRUE(spike);
  // A large simple polygon (a 20,000-gon) is accepted quickly; the same with two vertices swapped is not.
  std::vector<Vec2> round;
  round.reserve(20000);
  for (int k = 0; k < 20000; ++k)
    round.emplace_back(100 * std::cos(2 * kPi * k / 20000), 100 * std::sin(2 * kPi * k / 20000));
  EXPECT_FALSE(polygon_self_intersection(round));
  std::swap(round[10], round[5000]);
  EXPECT_TRUE(polygon_self_intersection(round));
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

// The rectangle less a polygon that reaches its four sides: pieces whose areas add up to the
// rectangle's less the polygon's, none with a hole.
TEST(Geometry, RectangleMinusPolygonLeavesTheCorners) {
  const std::vector<Vec2> diamond = {{5, 0}, {10, 5}, {5, 10}, {0, 5}};
  bool holes = true;
  const auto pieces = rectangle_minus_polygon(Vec2(0, 0), Vec2(10, 10), diamond, &holes);
  EXPECT_FALSE(holes);
  ASSERT_EQ(pieces.size(), 4u);
  double area = 0.0;
  for (const auto& p : pieces) area += std::abs(polygon_signed_area(p));
  EXPECT_NEAR(area, 100.0 - 50.0, 1e-9);
  // A polygon inside, touching no side: one piece with a hole, said so.
  const std::vector<Vec2> inner = {{2, 2}, {8, 2}, {8, 8}, {2, 8}};
  rectangle_minus_polygon(Vec2(0, 0), Vec2(10, 10), inner, &holes);
  EXPECT_TRUE(holes);
}

}  // namespace
}  // namespace uavplan
