#include "uavplan/planning/problem.h"

namespace uavplan {

double Route::length_m() const {
  double len = 0.0;
  for (std::size_t i = 1; i < waypoints.size(); ++i) len += (waypoints[i] - waypoints[i - 1]).norm();
  return len;
}

}  // namespace uavplan
