// The soak: thousands of random worlds per registered planner (and per mission type that plans
// with its own method), each planned with a 2 s stop and checked: a UAV a planner calls solved
// must pass the verifier before the verifier may fail it. Prints the table; the make-test
// property tests run a few hundred of the same.
#pragma once

#include <cstdint>
#include <string>

namespace uavplan::bench {

struct SoakOptions {
  int worlds = 1000;  // per planner
  std::uint64_t seed = 1;
};

// The table; all_held is false when any claim failed the verifier.
std::string run_soak(const SoakOptions& options, bool* all_held = nullptr);

}  // namespace uavplan::bench
