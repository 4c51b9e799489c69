#include "uavplan/world/world.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "uavplan/core/geometry.h"

namespace uavplan {
namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

void validate(const WorldSpec& s) {
  if (!finite(s.bounds.min) || !finite(s.bounds.max) || (s.bounds.min.array() > s.bounds.max.array()).any())
    throw std::invalid_argument("world bounds must be finite with min <= max on every axis");
  for (std::size_t i = 0; i < s.obstacles.size(); ++i) {
    const Aabb box = bounding_box(s.obstacles[i]);
    const std::string where = "obstacle " + std::to_string(i) + ": ";
    if (box.empty() || !finite(box.min) || !finite(box.max))
      throw std::invalid_argument(where + "empty or non-finite shape");
    if (const auto* p = std::get_if<Prism>(&s.obstacles[i])) {
      if (p->polygon.size() < 3) throw std::invalid_argument(where + "a prism needs at least 3 vertices");
      if (std::abs(polygon_signed_area(p->polygon)) <= 0.0)
        throw std::invalid_argument(where + "prism polygon has zero area");
    }
  }
  for (const auto& m : s.moving) {
    if (!(m.radius_m >= 0.0) || !finite(m.position) || !finite(m.velocity_mps))
      throw std::invalid_argument("moving obstacle '" + m.id + "': bad radius, position or velocity");
    if (m.path.size() == 1) throw std::invalid_argument("moving obstacle '" + m.id + "': a path needs at least 2 rows");
    for (std::size_t k = 0; k < m.path.size(); ++k) {
      if (!std::isfinite(m.path[k].t_s) || !finite(m.path[k].p))
        throw std::invalid_argument("moving obstacle '" + m.id + "': non-finite path row " + std::to_string(k));
      if (k > 0 && !(m.path[k].t_s > m.path[k - 1].t_s))
        throw std::invalid_argument("moving obstacle '" + m.id + "': path times must increase (row " +
                                    std::to_string(k) + ")");
    }
  }
  for (const auto& r : s.radars)
    if (!finite(r.position) || !std::isfinite(r.weight) || r.weight < 0.0)
      throw std::invalid_argument("radar: bad position or weight");
}

std::vector<Aabb> boxes_of(const std::vector<Obstacle>& obstacles) {
  std::vector<Aabb> boxes;
  boxes.reserve(obstacles.size());
  for (const auto& o : obstacles) boxes.push_back(bounding_box(o));
  return boxes;
}

}  // namespace

World::World(WorldSpec spec) : spec_(std::move(spec)) {
  validate(spec_);
  const auto boxes = boxes_of(spec_.obstacles);
  bvh_ = Bvh(boxes);
}

std::string World::obstacle_label(std::size_t k) const {
  const auto& ids = spec_.obstacle_ids;
  if (k < ids.size() && !ids[k].empty()) return "obstacle " + ids[k];
  return "obstacle " + std::to_string(k) + " (" + std::string(shape_name(spec_.obstacles.at(k))) + ")";
}

std::string World::nearest_label(const Vec3& p) const {
  double best = kInf;
  std::string what = "an obstacle";
  for (std::size_t k = 0; k < spec_.obstacles.size(); ++k) {
    const double d = point_distance(spec_.obstacles[k], p);
    if (d >= best) continue;
    best = d;
    what = obstacle_label(k);
  }
  if (spec_.terrain && spec_.terrain->point_distance(p, best) < best) what = kTerrainLabel;
  return what;
}

double World::clearance(const Vec3& p, double cap) const {
  double best = cap;
  if (spec_.terrain) best = spec_.terrain->point_distance(p, best);
  bvh_.visit_point(p, best, [&](std::int32_t i, double& radius) {
    radius = std::min(radius, point_distance(spec_.obstacles[i], p));
    return radius <= 0.0;
  });
  return best;
}

double World::segment_clearance(const Vec3& a, const Vec3& b, double cap) const {
  double best = cap;
  if (spec_.terrain) best = spec_.terrain->segment_distance(a, b, best);
  if (best <= 0.0) return 0.0;
  bvh_.visit_segment(a, b, best, [&](std::int32_t i, double& radius) {
    radius = std::min(radius, segment_distance(spec_.obstacles[i], a, b, radius));
    return radius <= 0.0;
  });
  return best;
}

double World::segment_obstacle_clearance(const Vec3& a, const Vec3& b, double cap) const {
  double best = cap;
  bvh_.visit_segment(a, b, best, [&](std::int32_t i, double& radius) {
    radius = std::min(radius, segment_distance(spec_.obstacles[i], a, b, radius));
    return radius <= 0.0;
  });
  return best;
}

double World::ground_z(double x, double y) const {
  const double floor = spec_.bounds.min.z();
  if (!spec_.terrain) return floor;
  const double h = spec_.terrain->height_at(x, y);
  return std::isfinite(h) ? std::max(h, floor) : floor;
}

double World::ground_leg_clearance(const Vec3& a, const Vec3& b, double keep, double ground_z) const {
  double c = segment_obstacle_clearance(a, b, keep);
  const double above = ground_z + keep;
  double s0 = 0.0, s1 = 1.0;
  if (b.z() != a.z()) {
    const double s = (above - a.z()) / (b.z() - a.z());
    if (b.z() > a.z())
      s0 = std::max(s0, s);
    else
      s1 = std::min(s1, s);
  } else if (a.z() < above) {
    return c;
  }
  if (s0 < s1) c = std::min(c, segment_clearance(a + s0 * (b - a), a + s1 * (b - a), keep));
  return c;
}

double World::lowest_height_above_ground(const Vec3& a, const Vec3& b) const {
  const double floor = std::min(a.z(), b.z()) - spec_.bounds.min.z();
  if (!spec_.terrain) return floor;
  return std::min(floor, spec_.terrain->lowest_height_above(a, b));
}

double World::highest_height_above_ground(const Vec3& a, const Vec3& b) const {
  const double floor = spec_.bounds.min.z();
  if (!spec_.terrain) return std::max(a.z(), b.z()) - floor;
  return spec_.terrain->highest_height_above(a, b, floor);
}

double World::moving_clearance(const Vec3& a, double t_a_s, const Vec3& b, double t_b_s, int* index_out) const {
  double best = kInf;
  const double span = t_b_s - t_a_s;
  auto uav_at = [&](double t) { return span > 0.0 ? Vec3(a + (t - t_a_s) / span * (b - a)) : a; };
  for (std::size_t k = 0; k < spec_.moving.size(); ++k) {
    const MovingObstacle& m = spec_.moving[k];
    // Between the obstacle's rows the relative position is linear in time, so the minimum norm
    // of each piece is exact.
    double gap = kInf;
    Vec3 d0 = a - m.position_at(t_a_s);
    for (const TimedPoint& row : m.rows()) {
      if (row.t_s <= t_a_s) continue;
      if (row.t_s >= t_b_s) break;
      const Vec3 d1 = uav_at(row.t_s) - row.p;
      gap = std::min(gap, point_segment_distance(Vec3::Zero(), d0, d1));
      d0 = d1;
    }
    gap = std::min(gap, point_segment_distance(Vec3::Zero(), d0, Vec3(b - m.position_at(t_b_s)))) - m.radius_m;
    if (gap < best) {
      best = gap;
      if (index_out) *index_out = static_cast<int>(k);
    }
  }
  return best;
}

}  // namespace uavplan
