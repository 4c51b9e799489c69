#include "uavplan/planning/smoothing/shortcut.h"

namespace uavplan {

std::vector<Vec3> shortcut(std::span<const Vec3> pts, std::span<const char> pinned, const SegmentPredicate& ok) {
  std::vector<Vec3> out;
  const std::size_t n = pts.size();
  if (n == 0) return out;
  out.push_back(pts[0]);
  // After a failed look, a few more are tried: visibility along a grid path is nearly, but not
  // exactly, monotone.
  constexpr int kExtraLooks = 3;
  std::size_t a = 0;
  while (a + 1 < n) {
    std::size_t best = a + 1;
    int misses = 0;
    for (std::size_t j = a + 2; j < n; ++j) {
      if (pinned[j - 1]) break;
      if (ok(pts[a], pts[j])) {
        best = j;
        misses = 0;
      } else if (++misses > kExtraLooks) {
        break;
      }
    }
    out.push_back(pts[best]);
    a = best;
  }
  return out;
}

}  // namespace uavplan
