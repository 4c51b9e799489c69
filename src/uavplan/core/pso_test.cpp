#include "uavplan/core/pso.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace uavplan {
namespace {

double sphere_at(std::span<const double> x) { return std::hypot(x[0] - 3.0, x[1] + 2.0); }

TEST(Pso, FindsTheMinimumInsideTheBoxAndIsRepeatable) {
  const std::array<double, 2> lo{-10, -10}, hi{10, 10};
  Rng a(7), b(7);
  const PsoResult r = pso_minimize(sphere_at, lo, hi, {}, a), again = pso_minimize(sphere_at, lo, hi, {}, b);
  EXPECT_LT(r.f, 1e-3);
  EXPECT_EQ(r.x, again.x);
  EXPECT_EQ(r.evaluations, 30 * 101);
}

TEST(Pso, StaysInTheBoxAndStopsWhenStalled) {
  // The minimum (3, -2) lies outside [-1, 1]^2: the best is the box's corner (1, -1).
  const std::array<double, 2> lo{-1, -1}, hi{1, 1};
  PsoOptions o;
  o.stall_iterations = 10;
  Rng r(3);
  const PsoResult res = pso_minimize(sphere_at, lo, hi, o, r);
  EXPECT_NEAR(res.x[0], 1.0, 1e-9);
  EXPECT_NEAR(res.x[1], -1.0, 1e-9);
  EXPECT_LT(res.evaluations, 30 * 101);
}

TEST(Pso, DeathPenaltyKeepsToTheFeasibleSetAndASeedIsNeverLost) {
  // Feasible: x0 <= 0 only. Seeded with a feasible point.
  const auto f = [](std::span<const double> x) {
    return x[0] > 0.0 ? std::numeric_limits<double>::infinity() : sphere_at(x);
  };
  const std::array<double, 2> lo{-10, -10}, hi{10, 10}, seed{-5, 5};
  PsoOptions o;
  o.iterations = 0;  // the seed alone may be the best of a random first swarm
  Rng r(1);
  const PsoResult only_seed = pso_minimize(f, lo, hi, o, r, seed);
  EXPECT_LE(only_seed.f, sphere_at(seed));
  Rng r2(1);
  const PsoResult res = pso_minimize(f, lo, hi, {}, r2, seed);
  EXPECT_LE(res.x[0], 0.0);
  EXPECT_NEAR(res.f, std::hypot(3.0, 0.0), 1e-3);
}

}  // namespace
}  // namespace uavplan
