#include "uavplan/evaluation/ground_legs.h"

namespace uavplan {

GroundLegs ground_legs(const World& w, const Trajectory& tr) {
  GroundLegs g;
  const std::size_t n = tr.size();
  if (n < 2) return g;
  std::size_t first_air = n, last_air = n;
  for (std::size_t k = 0; k < n; ++k)
    if (!w.on_ground(tr[k].p)) {
      if (first_air == n) first_air = k;
      last_air = k;
    }
  if (first_air == n) return g;  // never leaves the ground
  g.takeoff = w.on_ground(tr.front().p);
  if (g.takeoff) {
    g.takeoff_end = first_air;
    while (g.takeoff_end + 1 < n && World::same_column(tr[g.takeoff_end + 1].p, tr.front().p)) ++g.takeoff_end;
  }
  g.landing = w.on_ground(tr.back().p);
  g.landing_begin = n - 1;
  if (g.landing) {
    g.landing_begin = last_air;
    while (g.landing_begin > 0 && World::same_column(tr[g.landing_begin - 1].p, tr.back().p)) --g.landing_begin;
  }
  if (g.takeoff && g.landing && g.takeoff_end > g.landing_begin) g.landing_begin = g.takeoff_end;
  return g;
}

}  // namespace uavplan
