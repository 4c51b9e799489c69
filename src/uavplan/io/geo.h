// The scenario's local frame (x east, y north, z up, metres) tied to WGS84 through its `origin`.
#pragma once

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/vec.h"

namespace uavplan {

struct LatLonAlt {
  double lat_deg = 0.0, lon_deg = 0.0;
  double alt_m = 0.0;  // origin.alt + z: metres above the origin's datum (mean sea level)
};

// The local frame on WGS84. Horizontally, x and y are a point on the origin's tangent plane
// (ENU), placed by GeographicLib's LocalCartesian (exact on the ellipsoid); its latitude and
// longitude are those of that point. Vertically, z is height above the origin's datum: the
// altitude is origin.alt + z exactly, without the earth's curvature (which would put a point
// at z = 0 330 m above the datum 65 km away) — what a pilot reads on an altimeter. No geoid
// model is applied (none ships offline): altitudes stay in the origin's datum.
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
