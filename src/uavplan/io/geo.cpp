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
  impl_->lc.Reverse(p.x(), p.y(), p.z(), g.lat_deg, g.lon_deg, g.alt_m);
  return g;
}

Vec3 GeoFrame::to_local(double lat_deg, double lon_deg, double alt_m) const {
  double x = 0, y = 0, z = 0;
  impl_->lc.Forward(lat_deg, lon_deg, alt_m, x, y, z);
  return {x, y, z};
}

}  // namespace uavplan
