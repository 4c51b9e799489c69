// Small statistics and the clock the benchmark tables share.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace uavplan::bench {

using Clock = std::chrono::steady_clock;

// Milliseconds since t0 on the steady clock.
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The upper median (the middle element of an odd count); 0 for none.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The nearest-rank p-th percentile (p in (0, 100]); 0 for none.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

}  // namespace uavplan::bench
