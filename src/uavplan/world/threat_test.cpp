#include "uavplan/world/threat.h"

#include <gtest/gtest.h>

#include <vector>

namespace uavplan {
namespace {

TEST(Threat, P1ThreePointRule) {
  // A 6 m edge along x, a threat 1 m off its middle: sample points at x = 1, 3, 5.
  const std::vector<Radar> radars{{Vec3(3, 1, 0), 2.0}};
  const double d1 = std::hypot(2.0, 1.0), d2 = 1.0;
  const double expected = 6.0 * 2.0 * (2.0 / std::pow(d1, 4) + 1.0 / std::pow(d2, 4));
  EXPECT_NEAR(p1_threat_cost(Vec3(0, 0, 0), Vec3(6, 0, 0), radars), expected, 1e-12);
}

TEST(Threat, IntegralMatchesQuadrature) {
  const std::vector<Radar> radars{{Vec3(3, 1, 0.5), 1.0}, {Vec3(-2, 4, 1), 3.0}};
  const Vec3 a(0, 0, 0), b(7, 2, 1);
  double q = 0.0;
  const int n = 200000;
  const double len = (b - a).norm();
  for (int i = 0; i < n; ++i) q += threat_density(a + (b - a) * ((i + 0.5) / n), radars) * len / n;  // midpoint rule
  EXPECT_NEAR(threat_integral(a, b, radars), q, 1e-6 * q);
}

TEST(Threat, DistanceIsClampedNotInfinite) {
  const std::vector<Radar> radars{{Vec3(1, 0, 0), 1.0}};
  const double c = threat_integral(Vec3(0, 0, 0), Vec3(2, 0, 0), radars);
  EXPECT_TRUE(std::isfinite(c));
  EXPECT_GT(c, 1e6);
}

}  // namespace
}  // namespace uavplan
