// P1's chaotic sampling: one logistic-map sequence x_{k+1} = mu x_k (1 - x_k) per coordinate
// (mu = 4, fully chaotic), so that the samples cover the whole region. At mu = 4 the map's
// invariant density is the arcsine law, not uniform; u = (2/pi) asin(sqrt(x)) makes it uniform
// (an option). Seeds come from an Rng and avoid the map's fixed points and their preimages
// (0, 1/4, 1/2, 3/4, 1); an orbit that floating point collapses onto 0, 1 or a short cycle is
// re-seeded.
#pragma once

#include <array>

#include "uavplan/core/rng.h"
#include "uavplan/core/vec.h"

namespace uavplan {

class ChaoticSampler {
 public:
  ChaoticSampler(std::uint64_t seed, bool arcsine_to_uniform, double mu = 4.0);

  // The next value in [0, 1] of coordinate `axis` (0, 1, 2).
  double next(int axis);
  // A point of the box, one chaotic value per axis (a flat axis keeps the box's value).
  Vec3 sample(const Aabb& box);
  int reseeds() const { return reseeds_; }

 private:
  double fresh_seed();
  Rng rng_;
  bool uniform_;
  double mu_;
  std::array<double, 3> x_{}, prev_{}, prev2_{};
  int reseeds_ = 0;
};

}  // namespace uavplan
