#include "uavplan/planning/sampling/chaotic_sampler.h"

#include <gtest/gtest.h>

#include <set>

namespace uavplan {
namespace {

std::array<int, 10> histogram(ChaoticSampler& s, int n) {
  std::array<int, 10> h{};
  for (int i = 0; i < n; ++i) ++h[std::min(9, static_cast<int>(s.next(0) * 10))];
  return h;
}

TEST(ChaoticSampler, LogisticMapHasTheArcsineDensityAndTheTransformMakesItUniform) {
  ChaoticSampler raw(11, false), uniform(11, true);
  const auto hr = histogram(raw, 200000), hu = histogram(uniform, 200000);
  // The arcsine law puts ~20.5 % in each outer tenth and ~6.4 % in each middle one (papers.md P1).
  EXPECT_GT(hr[0], 38000);
  EXPECT_GT(hr[9], 38000);
  EXPECT_LT(hr[4], 15000);
  for (int b = 0; b < 10; ++b) EXPECT_NEAR(hu[b], 20000, 1200) << "bin " << b;
}

TEST(ChaoticSampler, NeverStallsOnAFixedPointAndIsSeeded) {
  ChaoticSampler a(3, false), b(3, false), c(4, false);
  std::set<double> seen;
  for (int i = 0; i < 100000; ++i) {
    const double x = a.next(1);
    EXPECT_EQ(x, b.next(1));
    ASSERT_GT(x, 0.0);
    ASSERT_LT(x, 1.0);
    if (i >= 99000) seen.insert(x);
  }
  EXPECT_GT(seen.size(), 990u) << "the orbit keeps moving";
  EXPECT_NE(ChaoticSampler(3, false).next(0), c.next(0));
}

TEST(ChaoticSampler, SamplesCoverTheBoxAndKeepFlatAxes) {
  ChaoticSampler s(9, true);
  const Aabb box{Vec3(10, -5, 7), Vec3(50, 40, 7)};
  Aabb seen;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 p = s.sample(box);
    ASSERT_TRUE(box.contains(p));
    seen.extend(p);
  }
  EXPECT_LT(seen.min.x(), 10.5);
  EXPECT_GT(seen.max.y(), 39.5);
  EXPECT_EQ(seen.min.z(), 7.0);
}

}  // namespace
}  // namespace uavplan
