#include "uavplan/coordination/contract/runway.h"

#include <algorithm>
#include <cmath>

#include "uavplan/coordination/contract/separation.h"

namespace uavplan {
namespace {

// A point in the runway's frame: along the centreline from the threshold, to its left, above it.
Vec3 runway_frame(const Airfield& af, const Vec3& p) {
  const double c = std::cos(af.runway_heading_rad), s = std::sin(af.runway_heading_rad);
  const Vec3 d = p - af.position;
  return {c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z()};
}

// Narrows [lo, hi] to the s in which a + s (b - a) <= limit (one coordinate).
void clip_below(double a, double b, double limit, double& lo, double& hi) {
  if (a == b) {
    if (a > limit) hi = -1.0;
    return;
  }
  const double s = (limit - a) / (b - a);
  if (b > a)
    hi = std::min(hi, s);
  else
    lo = std::max(lo, s);
}

}  // namespace

bool on_runway(const Airfield& af, const Vec3& p) {
  const Vec3 r = runway_frame(af, p);
  return r.x() >= 0.0 && r.x() <= af.runway_length_m && std::abs(r.y()) <= kRunwayHalfWidth_m &&
         r.z() <= kAirborneAbove_m;
}

std::vector<TimeSpan> runway_occupancy(const Airfield& af, const Trajectory& tr) {
  std::vector<TimeSpan> out;
  const auto add = [&](double from, double to) {
    if (!out.empty() && from <= out.back().to_s + kRunwayOverlap_s)
      out.back().to_s = std::max(out.back().to_s, to);
    else
      out.push_back({from, to});
  };
  if (tr.size() == 1 && on_runway(af, tr[0].p)) add(tr[0].t_s, tr[0].t_s);
  for (std::size_t k = 0; k + 1 < tr.size(); ++k) {
    const Vec3 a = runway_frame(af, tr[k].p), b = runway_frame(af, tr[k + 1].p);
    double lo = 0.0, hi = 1.0;
    clip_below(-a.x(), -b.x(), 0.0, lo, hi);  // along >= 0
    clip_below(a.x(), b.x(), af.runway_length_m, lo, hi);
    clip_below(a.y(), b.y(), kRunwayHalfWidth_m, lo, hi);
    clip_below(-a.y(), -b.y(), kRunwayHalfWidth_m, lo, hi);
    clip_below(a.z(), b.z(), kAirborneAbove_m, lo, hi);
    if (lo > hi) continue;
    const double dt = tr[k + 1].t_s - tr[k].t_s;
    add(tr[k].t_s + lo * dt, tr[k].t_s + hi * dt);
  }
  return out;
}

std::optional<TimeSpan> runway_overlap(const std::vector<TimeSpan>& a, const std::vector<TimeSpan>& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double from = std::max(a[i].from_s, b[j].from_s), to = std::min(a[i].to_s, b[j].to_s);
    if (to - from > kRunwayOverlap_s) return TimeSpan{from, to};
    if (a[i].to_s < b[j].to_s)
      ++i;
    else
      ++j;
  }
  return std::nullopt;
}

}  // namespace uavplan
