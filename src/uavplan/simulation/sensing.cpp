#include "uavplan/simulation/sensing.h"

#include <algorithm>
#include <cmath>

namespace uavplan {

Vec3 ground_velocity(const Vec3& rel0, const Vec3& rel1, const Vec3& own0, const Vec3& own1, double dt_s) {
  return ((rel1 - rel0) + (own1 - own0)) / dt_s;
}

void sense(Sensor& sensor, std::span<const ObjectState> truth, std::size_t self, const Vec3& own, double t_s) {
  std::vector<Track> next;
  const auto earlier = [&](std::size_t i) -> const Track* {
    for (const auto* list : {&sensor.tracks, &sensor.lost})
      for (const Track& k : *list)
        if (k.object == i && k.seen_s < t_s) return &k;
    return nullptr;
  };
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i == self) continue;
    const ObjectState& o = truth[i];
    const Vec3 rel = o.position - own;
    if (rel.norm() - o.radius_m > sensor.range_m) continue;
    Track t{i, o.id, o.radius_m, o.is_uav, t_s, rel, own, std::nullopt, 0.0};
    if (const Track* prev = earlier(i)) {
      t.velocity_mps = ground_velocity(prev->relative_m, rel, prev->own_m, own, t_s - prev->seen_s);
    } else if (sensor.last_own_m && t_s > sensor.last_s && std::isfinite(sensor.range_m)) {
      const double was = (o.position - *sensor.last_own_m).norm();
      t.entered_speed_mps = std::max(0.0, (sensor.range_m + o.radius_m - was) / (t_s - sensor.last_s));
    }
    next.push_back(std::move(t));
  }
  // Objects that left the range are remembered by their last observation.
  for (Track& k : sensor.tracks)
    if (std::none_of(next.begin(), next.end(), [&](const Track& n) { return n.object == k.object; })) {
      std::erase_if(sensor.lost, [&](const Track& l) { return l.object == k.object; });
      sensor.lost.push_back(std::move(k));
    }
  std::erase_if(sensor.lost, [&](const Track& l) {
    return std::any_of(next.begin(), next.end(), [&](const Track& n) { return n.object == l.object; });
  });
  sensor.tracks = std::move(next);
  sensor.last_own_m = own;
  sensor.last_s = t_s;
}

}  // namespace uavplan
