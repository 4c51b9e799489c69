// What every route segment a planner emits must satisfy: inside the bounds, under the ceiling,
// clear of static obstacles after inflation (plus a small planning margin, so rounding in the
// written plan cannot touch an obstacle) and within the climb limit.
#pragma once

#include <algorithm>

#include "uavplan/vehicle/uav.h"
#include "uavplan/world/world.h"

namespace uavplan {

// Margin added to the UAV radius while planning, in metres.
inline constexpr double kPlanningMargin_m = 1e-3;

class SegmentRule {
 public:
  SegmentRule(const World& world, const UavSpec& uav)
      : world_(&world),
        inflation_m_(uav.radius_m + kPlanningMargin_m),
        max_climb_rad_(uav.max_climb_rad),
        // |pitch| <= limit + tolerance as |dz| <= horizontal * tan(limit + tolerance): no atan2 per segment.
        tan_climb_(max_climb_rad_ + kAngleTolerance_rad < kPi / 2 ? std::tan(max_climb_rad_ + kAngleTolerance_rad)
                                                                  : -1.0),
        ceiling_m_(uav.ceiling_m ? std::min(*uav.ceiling_m, world.bounds().max.z()) : world.bounds().max.z()) {}

  // Keeps points this far inside the bounds' sides (a body or a turn's overshoot that must stay in).
  SegmentRule with_edge_margin(double margin_m) const {
    SegmentRule r = *this;
    r.edge_m_ = std::max(0.0, margin_m);
    return r;
  }

  bool point_ok(const Vec3& p) const {
    return inside(p) && p.z() <= ceiling_m_ && !world_->point_collides(p, inflation_m_);
  }
  bool operator()(const Vec3& a, const Vec3& b) const {
    return limits_ok(a, b) && !world_->segment_collides(a, b, inflation_m_);
  }
  // Everything but the obstacles and terrain: inside, under the ceiling, within the climb limit.
  bool limits_ok(const Vec3& a, const Vec3& b) const {
    if (!inside(a) || !inside(b)) return false;
    if (a.z() > ceiling_m_ || b.z() > ceiling_m_) return false;
    return tan_climb_ < 0.0 || std::abs(b.z() - a.z()) <= tan_climb_ * (b - a).head<2>().norm();
  }
  double inflation_m() const { return inflation_m_; }
  double ceiling_m() const { return ceiling_m_; }
  double edge_margin_m() const { return edge_m_; }
  double max_climb_rad() const { return max_climb_rad_; }
  const World& world() const { return *world_; }

 private:
  bool inside(const Vec3& p) const {
    if (!world_->in_bounds(p)) return false;
    const Aabb& b = world_->bounds();
    return edge_m_ <= 0.0 || (p.x() >= b.min.x() + edge_m_ && p.x() <= b.max.x() - edge_m_ &&
                              p.y() >= b.min.y() + edge_m_ && p.y() <= b.max.y() - edge_m_);
  }

  const World* world_;
  double inflation_m_;
  double max_climb_rad_;
  double tan_climb_;  // negative: no climb limit
  double ceiling_m_;
  double edge_m_ = 0.0;
};

}  // namespace uavplan
