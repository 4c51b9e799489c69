// Small statistics the benchmark tables share.
#pragma once

#include <algorithm>
#include <vector>

namespace uavplan::bench {

// The upper median (the middle element of an odd count); 0 for none.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace uavplan::bench
