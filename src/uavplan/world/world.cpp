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
  for (const auto& m : s.moving)
    if (!(m.radius_m >= 0.0) || !finite(m.position) || !finite(m.velocity_mps))
      throw std::invalid_argument("moving obstacle '" + m.id + "': bad radius, position or velocity");
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
    radius = std::min(radius, segment_distance(spec_.obstacles[i], a, b));
    return radius <= 0.0;
  });
  return best;
}

double World::moving_clearance(const Vec3& a, double t_a_s, const Vec3& b, double t_b_s, int* index_out) const {
  double best = kInf;
  for (std::size_t k = 0; k < spec_.moving.size(); ++k) {
    const MovingObstacle& m = spec_.moving[k];
    // Relative position is linear in the segment parameter, so its minimum norm is exact.
    const Vec3 d0 = a - m.position_at(t_a_s);
    const Vec3 d1 = b - m.position_at(t_b_s);
    const double gap = point_segment_distance(Vec3::Zero(), d0, d1) - m.radius_m;
    if (gap < best) {
      best = gap;
      if (index_out) *index_out = static_cast<int>(k);
    }
  }
  return best;
}

}  // namespace uavplan
