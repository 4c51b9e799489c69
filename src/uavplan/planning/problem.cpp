#include "uavplan/planning/problem.h"

namespace uavplan {

double Route::length_m() const {
  double len = 0.0;
  for (std::size_t i = 1; i < waypoints.size(); ++i) len += (waypoints[i] - waypoints[i - 1]).norm();
  return len;
}

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
