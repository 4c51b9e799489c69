#include "uavplan/coordination/contract/separation.h"

#include <algorithm>
#include <cmath>

namespace uavplan {

double required_separation_m(const Scenario& sc, const UavSpec& a, const UavSpec& b) {
  return std::max(sc.mission.separation_m, a.radius_m + b.radius_m);
}

}  // namespace uavplan

namespace uavplan {

AirfieldEncounter airfield_encounter(const Scenario& sc, const UavSpec& ua, const Trajectory& a, const UavSpec& ub,
                                     const Trajectory& b, double from_s) {
  AirfieldEncounter out;
  if (a.empty() || b.empty()) return out;
  const double ground_z = sc.mission.airfield ? sc.mission.airfield->position.z() : sc.world.bounds().min.z();
  const double sep = std::max(sc.mission.separation_m, ua.radius_m + ub.radius_m), bodies = ua.radius_m + ub.radius_m;
  const auto high = [&](const Vec3& p) { return p.z() > ground_z + kAirborneAbove_m; };
  const double t_end = std::min(a.back().t_s, b.back().t_s);
  // The merged row times from `from_s` to the first UAV's last row.
  std::vector<double> times{std::max(from_s, std::min(a.front().t_s, b.front().t_s))};
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const double t = j >= b.size() || (i < a.size() && a[i].t_s <= b[j].t_s) ? a[i++].t_s : b[j++].t_s;
    if (t > times.back() && t <= t_end) times.push_back(t);
  }
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < times.size() || (k == 0 && times.size() == 1); ++k) {
    const double t0 = times[k], t1 = k + 1 < times.size() ? times[k + 1] : times[k];
    const Vec3 a0 = position_at(a, t0), a1 = position_at(a, t1), b0 = position_at(b, t0), b1 = position_at(b, t1);
    const double need = high(a0) || high(a1) || high(b0) || high(b1) ? sep : bodies;
    const Vec3 d0 = a0 - b0, dd = (a1 - b1) - d0;
    const double s = dd.squaredNorm() > 0.0 ? std::clamp(-d0.dot(dd) / dd.squaredNorm(), 0.0, 1.0) : 0.0;
    const double dist = (d0 + s * dd).norm();
    if (need == sep) out.airborne_min_m = std::min(out.airborne_min_m, dist);
    if (need - dist > worst + 1e-6) {
      worst = need - dist;
      out.conflict = true;
      out.t_s = t0 + s * (t1 - t0), out.distance_m = dist, out.need_m = need, out.where = a0 + s * (a1 - a0);
    }
  }
  return out;
}

}  // namespace uavplan
