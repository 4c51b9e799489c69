// Soft threats (radar points): they cost, they do not forbid.
#pragma once

#include <span>

#include "uavplan/core/vec.h"

namespace uavplan {

struct Radar {
  Vec3 position;
  double weight = 1.0;  // multiplies the inverse-fourth-power cost
};

// Distances below this are clamped so that a route through a radar has a large, finite cost.
inline constexpr double kMinThreatDistance_m = 1e-3;

// Threat density sum_j w_j / d_j^4 at p.
double threat_density(const Vec3& p, std::span<const Radar> radars);

// P1 eq. 1 three-point rule: L * sum_j w_j (1/d(1/6)^4 + 1/d(1/2)^4 + 1/d(5/6)^4), with d the
// distance from the points at 1/6, 1/2 and 5/6 of the edge to threat j.
double p1_threat_cost(const Vec3& a, const Vec3& b, std::span<const Radar> radars);

// The exact integral of sum_j w_j / d_j^4 along the segment (closed form per threat).
double threat_integral(const Vec3& a, const Vec3& b, std::span<const Radar> radars);

}  // namespace uavplan
