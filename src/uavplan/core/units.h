// Angles and units. Files use degrees; the code uses radians everywhere.
#pragma once

#include <cmath>
#include <numbers>

namespace uavplan {

inline constexpr double kPi = std::numbers::pi;

constexpr double deg_to_rad(double deg) { return deg * kPi / 180.0; }
constexpr double rad_to_deg(double rad) { return rad * 180.0 / kPi; }

// Wraps an angle to (-pi, pi].
inline double wrap_angle_rad(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace uavplan
