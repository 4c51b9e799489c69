#include "uavplan/planning/sampling/chaotic_sampler.h"

#include <cmath>

#include "uavplan/core/units.h"

namespace uavplan {
namespace {

// Fixed points of mu = 4 (0 and 3/4) and the points that reach them in one or two steps.
bool near_fixed(double x) {
  for (const double f : {0.0, 0.25, 0.5, 0.75, 1.0})
    if (std::abs(x - f) < 1e-3) return true;
  return false;
}

}  // namespace

ChaoticSampler::ChaoticSampler(std::uint64_t seed, bool arcsine_to_uniform, double mu)
    : rng_(seed), uniform_(arcsine_to_uniform), mu_(mu) {
  for (int a = 0; a < 3; ++a) x_[a] = prev_[a] = prev2_[a] = fresh_seed();
}

double ChaoticSampler::fresh_seed() {
  double x;
  do {
    x = rng_.uniform(0.01, 0.99);
  } while (near_fixed(x));
  return x;
}

double ChaoticSampler::next(int axis) {
  double& x = x_[axis];
  prev2_[axis] = prev_[axis];
  prev_[axis] = x;
  x = mu_ * x * (1.0 - x);
  // Floating point ends every orbit on 0 (through 1/2 -> 1 -> 0), the fixed point 3/4 or a short
  // cycle: start a fresh one.
  if (x <= 1e-12 || x >= 1.0 - 1e-12 || x == prev_[axis] || x == prev2_[axis]) {
    x = fresh_seed();
    ++reseeds_;
  }
  return uniform_ ? 2.0 / kPi * std::asin(std::sqrt(x)) : x;
}

Vec3 ChaoticSampler::sample(const Aabb& box) {
  Vec3 p;
  for (int a = 0; a < 3; ++a) {
    const double lo = box.min[a], hi = box.max[a];
    p[a] = hi > lo ? lo + next(a) * (hi - lo) : lo;
  }
  return p;
}

}  // namespace uavplan
