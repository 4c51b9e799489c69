#include "uavplan/io/gdal_session.h"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>

namespace uavplan {

void register_gdal_drivers() {
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
}

QuietGdal::QuietGdal() {
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
}

QuietGdal::~QuietGdal() { CPLPopErrorHandler(); }

std::string gdal_said() {
  const std::string m = CPLGetLastErrorMsg();
  return m.empty() ? std::string() : " (GDAL: " + m + ")";
}

}  // namespace uavplan
