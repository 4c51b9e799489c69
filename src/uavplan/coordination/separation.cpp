#include "uavplan/coordination/separation.h"

#include <algorithm>
#include <cmath>

namespace uavplan {

double required_separation_m(const Scenario& sc, const UavSpec& a, const UavSpec& b) {
  return std::max(sc.mission.separation_m, a.radius_m + b.radius_m);
}

double separation_horizon_s(const Scenario& sc, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                            const Trajectory& tb) {
  const double need = required_separation_m(sc, a, b);
  if (!a.goal || !b.goal || (*a.goal - *b.goal).norm() >= need || ta.empty() || tb.empty()) return World::kInf;
  // The first time the trajectory comes within `need` of the goal, between samples too (a last
  // sample far out would otherwise leave the approach itself checked).
  auto entering = [&](const Trajectory& tr) {
    if ((tr.front().p - *a.goal).norm() <= need) return tr.front().t_s;
    for (std::size_t k = 1; k < tr.size(); ++k) {
      if ((tr[k].p - *a.goal).norm() > need) continue;
      // |f + s d| = need on this segment, the smaller root: where it enters the sphere.
      const Vec3 d = tr[k].p - tr[k - 1].p, f = tr[k - 1].p - *a.goal;
      const double aa = d.squaredNorm(), bb = f.dot(d), cc = f.squaredNorm() - need * need;
      const double disc = std::max(bb * bb - aa * cc, 0.0);
      const double s = aa > 0.0 ? std::clamp((-bb - std::sqrt(disc)) / aa, 0.0, 1.0) : 1.0;
      return tr[k - 1].t_s + s * (tr[k].t_s - tr[k - 1].t_s);
    }
    return tr.back().t_s;
  };
  return std::min(entering(ta), entering(tb));
}

}  // namespace uavplan
