#include "uavplan/io/geo.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geodesic.hpp>

namespace uavplan {

struct GeoFrame::Impl {
  GeographicLib::AzimuthalEquidistant projection{GeographicLib::Geodesic::WGS84()};
};

GeoFrame::GeoFrame(const GeoOrigin& origin) : origin_(origin), impl_(new Impl) {}

GeoFrame::~GeoFrame() { delete impl_; }

LatLonAlt GeoFrame::to_wgs84(const Vec3& p) const {
  LatLonAlt g;
  impl_->projection.Reverse(origin_.lat_deg, origin_.lon_deg, p.x(), p.y(), g.lat_deg, g.lon_deg);
  g.alt_m = origin_.alt_m + p.z();
  return g;
}

Vec3 GeoFrame::to_local(double lat_deg, double lon_deg, double alt_m) const {
  double x = 0, y = 0;
  impl_->projection.Forward(origin_.lat_deg, origin_.lon_deg, lat_deg, lon_deg, x, y);
  return {x, y, alt_m - origin_.alt_m};
}

}  // namespace uavplan
