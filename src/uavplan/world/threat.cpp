#include "uavplan/world/threat.h"

#include <cmath>

namespace uavplan {

double threat_density(const Vec3& p, std::span<const Radar> radars) {
  double sum = 0.0;
  for (const Radar& r : radars) {
    const double d2 = std::max((p - r.position).squaredNorm(), kMinThreatDistance_m * kMinThreatDistance_m);
    sum += r.weight / (d2 * d2);
  }
  return sum;
}

double p1_threat_cost(const Vec3& a, const Vec3& b, std::span<const Radar> radars) {
  const Vec3 ab = b - a;
  const double sum = threat_density(a + ab / 6.0, radars) + threat_density(a + ab / 2.0, radars) +
                     threat_density(a + ab * (5.0 / 6.0), radars);
  return ab.norm() * sum;
}

double threat_integral(const Vec3& a, const Vec3& b, std::span<const Radar> radars) {
  const Vec3 ab = b - a;
  const double len = ab.norm();
  if (len <= 0.0) return 0.0;
  const Vec3 u = ab / len;
  double total = 0.0;
  for (const Radar& r : radars) {
    // Along the line, d^2 = (s - s0)^2 + h^2; integral of ds / (s^2 + h^2)^2 is
    // s / (2 h^2 (s^2 + h^2)) + atan(s / h) / (2 h^3).
    const double s0 = (r.position - a).dot(u);
    const double h = std::max((a + s0 * u - r.position).norm(), kMinThreatDistance_m);
    auto antiderivative = [h](double s) {
      return s / (2.0 * h * h * (s * s + h * h)) + std::atan(s / h) / (2.0 * h * h * h);
    };
    total += r.weight * (antiderivative(len - s0) - antiderivative(-s0));
  }
  return total;
}

}  // namespace uavplan
