#include "uavplan/coordination/formation_mission/task_points.h"

#include <algorithm>
#include <cmath>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/core/geometry.h"

namespace uavplan {

const PhasedFormationSection& phased_section(const Scenario& sc) {
  static const PhasedFormationSection none;
  const PhasedFormationSection* s = sc.mission.section_as<PhasedFormationSection>();
  return s ? *s : none;
}

Trajectory formation_reference(const Scenario& sc, const std::vector<const Trajectory*>& trs) {
  const double ground = sc.mission.airfield ? sc.mission.airfield->position.z() : sc.world.bounds().min.z();
  std::vector<double> times;
  for (const Trajectory* tr : trs)
    for (const TrajectorySample& s : *tr) times.push_back(s.t_s);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  Trajectory ref;
  for (const double t : times) {
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (const Trajectory* tr : trs) {
      if (tr->empty() || t < tr->front().t_s || t > tr->back().t_s) continue;
      const Vec3 p = position_at(*tr, t);
      if (p.z() > ground + kAirborneAbove_m) sum += p, ++n;
    }
    if (n > 0) ref.push_back({t, sum / n});
  }
  return ref;
}

std::vector<TaskVisit> task_visits(const Scenario& sc, const Trajectory& ref) {
  std::vector<TaskVisit> out;
  std::size_t from = 0;
  const double tol = deg_to_rad(kTaskHeadingTolerance_deg);
  for (const TaskPoint& tp : phased_section(sc).task_points) {
    TaskVisit v;
    v.miss_m = World::kInf;
    for (std::size_t k = from; k + 1 < ref.size(); ++k) {
      const Vec3 &a = ref[k].p, &b = ref[k + 1].p;
      double t = 0.0;
      const double d = point_segment_distance(tp.position, a, b, &t);
      if (d > tp.radius_m) continue;
      const Vec2 dir = (b - a).head<2>();
      const double err = tp.entry_heading_rad && dir.norm() > 0.0
                             ? std::abs(wrap_angle_rad(std::atan2(dir.y(), dir.x()) - *tp.entry_heading_rad))
                             : 0.0;
      if (d < v.miss_m) v.miss_m = d, v.heading_error_rad = err;
      if (err <= tol) {
        v = {true, ref[k].t_s + t * (ref[k + 1].t_s - ref[k].t_s), d, err};
        from = k;
        break;
      }
    }
    out.push_back(v);
    if (!v.reached) break;
  }
  return out;
}

}  // namespace uavplan
