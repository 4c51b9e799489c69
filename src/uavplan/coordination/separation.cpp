#include "uavplan/coordination/separation.h"

#include <algorithm>
#include <cmath>

namespace uavplan {

double required_separation_m(const Scenario& sc, const UavSpec& a, const UavSpec& b) {
  return std::max(sc.mission.separation_m, a.radius_m + b.radius_m);
}

}  // namespace uavplan
