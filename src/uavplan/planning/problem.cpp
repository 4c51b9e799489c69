#include "uavplan/planning/problem.h"

#include "uavplan/core/geometry.h"

namespace uavplan {

double Route::length_m() const { return polyline_length_m(waypoints); }

std::string stop_name(std::size_t s, std::size_t stops) {
  if (s == 0) return "start";
  if (s + 1 >= stops) return "goal";
  return "via point " + std::to_string(s);
}

std::string leg_name(std::size_t leg, std::size_t stops) {
  const std::size_t legs = stops > 1 ? stops - 1 : 1;
  return "leg " + std::to_string(leg + 1) + (legs > 1 ? " of " + std::to_string(legs) : std::string()) + " (" +
         stop_name(leg, stops) + " to " + stop_name(leg + 1, stops) + ")";
}

}  // namespace uavplan
