#include "uavplan/io/geo.h"

#include <GeographicLib/LocalCartesian.hpp>

namespace uavplan {

struct GeoFrame::Impl {
  GeographicLib::LocalCartesian lc;
};

GeoFrame::GeoFrame(const GeoOrigin& origin)
    : origin_(origin), impl_(new Impl{GeographicLib::LocalCartesian(origin.lat_deg, origin.lon_deg, origin.alt_m)}) {}

GeoFrame::~GeoFrame() { delete impl_; }

LatLonAlt GeoFrame::to_wgs84(const Vec3& p) const {
  LatLonAlt g;
  double h = 0.0;  // the tangent-plane point's height over the ellipsoid: not an altitude
  impl_->lc.Reverse(p.x(), p.y(), 0.0, g.lat_deg, g.lon_deg, h);
  g.alt_m = origin_.alt_m + p.z();
  return g;
}

Vec3 GeoFrame::to_local(double lat_deg, double lon_deg, double alt_m) const {
  // The tangent-plane point whose latitude and longitude these are: Forward at the height that
  // point has over the ellipsoid, found by a few fixed-point steps (it moves x, y by x h / R).
  double x = 0, y = 0, z = 0, h = origin_.alt_m;
  for (int i = 0; i < 4; ++i) {
    impl_->lc.Forward(lat_deg, lon_deg, h, x, y, z);
    double lat = 0, lon = 0;
    impl_->lc.Reverse(x, y, 0.0, lat, lon, h);
  }
  return {x, y, alt_m - origin_.alt_m};
}

}  // namespace uavplan
