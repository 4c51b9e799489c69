// The scenario's local frame (x east, y north, z up, metres) tied to WGS84 through its `origin`.
#pragma once

#include "uavplan/coordination/scenario.h"
#include "uavplan/core/vec.h"

namespace uavplan {

struct LatLonAlt {
  double lat_deg = 0.0, lon_deg = 0.0;
  double alt_m = 0.0;  // origin.alt + z: metres above the origin's datum (mean sea level)
};

// Local tangent plane (ENU) at the origin, by GeographicLib's LocalCartesian: exact on the
// WGS84 ellipsoid, not a flat-earth approximation. Altitudes are treated as heights over the
// ellipsoid inside the transform; no geoid model is applied (none ships offline), so an
// altitude out is the origin's altitude plus the local height, in the origin's datum.
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
