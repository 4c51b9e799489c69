// The soak: thousands of random worlds per registered planner (and per mission type that plans
// with its own method), each planned with a stop (2 s by default) and checked: a UAV a planner
// calls solved must pass the verifier, and a plan must end within its stop + 0.2 s (a short stop
// makes the slow planners reach it). Prints the table; the make-test property tests run a few
// hundred of the same.
#pragma once

#include <cstdint>
#include <string>

namespace uavplan::bench {

struct SoakOptions {
  int worlds = 1000;  // per planner
  std::uint64_t seed = 1;
  double stop_s = 2.0;  // each plan's time limit
};

// How much later than its stop a plan may end.
inline constexpr double kSoakGraceS = 0.2;

// The table; all_held is false when any claim failed the verifier or any plan ended later than
// its stop + kSoakGraceS.
std::string run_soak(const SoakOptions& options, bool* all_held = nullptr);

}  // namespace uavplan::bench
