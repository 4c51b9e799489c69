#include "uavplan/vehicle/uav.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

namespace uavplan {
namespace {}

double pitch_rad(const Vec3& s) {
  const double h = s.head<2>().norm();
  if (h == 0.0 && s.z() == 0.0) return 0.0;
  return std::atan2(s.z(), h);
}

double turn_rad(const Vec3& from, const Vec3& to) {
  const double n1 = from.norm(), n2 = to.norm();
  if (n1 <= 0.0 || n2 <= 0.0) return 0.0;
  const double c = std::clamp(from.dot(to) / (n1 * n2), -1.0, 1.0);
  double angle = std::acos(c);
  const double h1 = from.head<2>().norm(), h2 = to.head<2>().norm();
  if (h1 > kSamePoint_m * n1 && h2 > kSamePoint_m * n2) {
    const double dyaw = wrap_angle_rad(std::atan2(to.y(), to.x()) - std::atan2(from.y(), from.x()));
    angle = std::max(angle, std::abs(dyaw));
  }
  return angle;
}

bool turn_within(const Vec3& from, const Vec3& to, double limit_rad) {
  const double n1 = from.norm(), n2 = to.norm();
  if (n1 <= 0.0 || n2 <= 0.0) return true;
  const double c = std::cos(limit_rad);  // both angles lie in [0, pi], where cos falls
  if (from.dot(to) < c * n1 * n2) return false;
  const double h1 = from.head<2>().norm(), h2 = to.head<2>().norm();
  if (h1 > kSamePoint_m * n1 && h2 > kSamePoint_m * n2) return from.head<2>().dot(to.head<2>()) >= c * h1 * h2;
  return true;
}

std::vector<LimitViolation> check_route_limits(std::span<const Vec3> pts, const UavSpec& uav) {
  std::vector<LimitViolation> out;
  std::optional<Vec3> prev;
  if (uav.heading_rad) prev = heading_vector(*uav.heading_rad);
  std::size_t vertex = 0;  // index of the waypoint where the current segment starts
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Vec3 seg = pts[i + 1] - pts[i];
    if (seg.norm() <= kSamePoint_m) continue;
    vertex = i;
    const double pitch = std::abs(pitch_rad(seg));
    if (pitch > uav.max_climb_rad + kAngleTolerance_rad) out.push_back({LimitViolation::Kind::climb, i, pitch});
    if (prev) {
      const double turn = turn_rad(*prev, seg);
      if (turn > uav.max_turn_rad + kAngleTolerance_rad) out.push_back({LimitViolation::Kind::turn, vertex, turn});
    }
    prev = seg;
  }
  return out;
}

}  // namespace uavplan
