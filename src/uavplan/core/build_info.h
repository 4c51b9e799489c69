// What kind of build this is, for tests that size their sweeps by it: under a sanitizer
// (AddressSanitizer, ThreadSanitizer) code runs 3-20 times slower, so the random-world property
// sweeps run a sample of their worlds there; the release build (`make test`) runs them whole.
#pragma once

#include <algorithm>
#include <cstdint>

namespace uavplan {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// How many of a sweep's `full` cases to run here: all of them, or under a sanitizer every
// eighth (at least `least`): what the sanitizers look for (memory and thread errors) shows on
// a sample, what the sweep measures is measured in release.
inline std::uint64_t sweep_cases(std::uint64_t full, std::uint64_t least = 2) {
  return kSanitizedBuild ? std::min(full, std::max<std::uint64_t>(least, full / 8)) : full;
}

}  // namespace uavplan
