// The scenario's local frame (x east, y north, z up, metres) tied to WGS84 through its `origin`.
#pragma once

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/vec.h"

namespace uavplan {

// Farther than any local map reaches from its origin: a file placed this far from the world is
// most likely placed through lat and lon swapped (here or in the origin).
inline constexpr double kFarBeyondAnyMap_m = 50'000.0;

struct LatLonAlt {
  double lat_deg = 0.0, lon_deg = 0.0;
  double alt_m = 0.0;  // origin.alt + z: metres above the origin's datum (mean sea level)
};

// The local frame on WGS84. Horizontally, (x, y) is GeographicLib's azimuthal equidistant
// projection about the origin on the WGS84 ellipsoid: the geodesic from the origin to a point
// has the point's distance sqrt(x^2 + y^2) and bearing atan2(x, y) exactly, at any range. Other
// distances shrink across the bearing only, by at most rho^2 / (6 R^2) of their length at range
// rho from the origin (R the earth's radius; kGroundShrinkPerRange2): 0.004 % at 100 km, 0.33 %
// at 900 km (P5's mission), so a verified separation of 50 m is 49.83 m on the ground there; a
// tangent plane would shorten a 900 km route by 6 km. Vertically, z is height above the
// origin's datum: the altitude is origin.alt + z exactly, without the earth's curvature (which
// would put a point at z = 0 330 m above the datum 65 km away) — what a pilot reads on an
// altimeter. No geoid model is applied (none ships offline): altitudes stay in the origin's datum.
// The relative shrink of ground distances at range rho: rho^2 times this (WGS84 mean radius).
inline constexpr double kGroundShrinkPerRange2 = 1.0 / (6.0 * 6'371'008.8 * 6'371'008.8);

class GeoFrame {
 public:
  explicit GeoFrame(const GeoOrigin& origin);
  ~GeoFrame();
  GeoFrame(const GeoFrame&) = delete;
  GeoFrame& operator=(const GeoFrame&) = delete;

  LatLonAlt to_wgs84(const Vec3& local_m) const;
  Vec3 to_local(double lat_deg, double lon_deg, double alt_m) const;
  const GeoOrigin& origin() const { return origin_; }

 private:
  struct Impl;
  GeoOrigin origin_;
  Impl* impl_;
};

}  // namespace uavplan
