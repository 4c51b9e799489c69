// Seeded random numbers whose distributions are our own, so the same seed gives the same
// numbers with any standard library (std:: distributions are implementation-defined).
#pragma once

#include <cstdint>

namespace uavplan {

// xoshiro256** (Blackman and Vigna), seeded through splitmix64.
class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1);

  std::uint64_t next_u64();
  // Uniform in [0, 1) with 53 random bits.
  double uniform01();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // Uniform integer in [lo, hi] (inclusive), without modulo bias.
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi);
  // Standard normal by Marsaglia's polar method, scaled.
  double normal(double mean = 0.0, double stddev = 1.0);
  // An independent stream derived from this generator's seed and `stream`, so parallel
  // workers get reproducible numbers whatever the thread count.
  Rng split(std::uint64_t stream) const;

 private:
  std::uint64_t seed_;
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace uavplan
