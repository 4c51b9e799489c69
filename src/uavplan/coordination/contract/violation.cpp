#include "uavplan/coordination/contract/violation.h"
#include "uavplan/core/text.h"

#include <cstdio>

namespace uavplan {

std::string_view to_string(ViolationKind k) {
  switch (k) {
    case ViolationKind::not_planned:
      return "not_planned";
    case ViolationKind::unknown_uav:
      return "unknown_uav";
    case ViolationKind::trajectory:
      return "trajectory";
    case ViolationKind::start:
      return "start";
    case ViolationKind::goal:
      return "goal";
    case ViolationKind::bounds:
      return "bounds";
    case ViolationKind::ceiling:
      return "ceiling";
    case ViolationKind::obstacle:
      return "obstacle";
    case ViolationKind::low_altitude:
      return "low_altitude";
    case ViolationKind::high_altitude:
      return "high_altitude";
    case ViolationKind::moving_obstacle:
      return "moving_obstacle";
    case ViolationKind::separation:
      return "separation";
    case ViolationKind::turn:
      return "turn";
    case ViolationKind::climb:
      return "climb";
    case ViolationKind::speed:
      return "speed";
    case ViolationKind::via_point:
      return "via_point";
    case ViolationKind::length_spread:
      return "length_spread";
    case ViolationKind::arrival_spread:
      return "arrival_spread";
    case ViolationKind::runway:
      return "runway";
  }
  return "?";
}

std::string describe(const Violation& v) {
  std::string s = v.uav.empty() ? std::string("mission") : v.uav;
  s += " ";
  s += to_string(v.kind);
  if (v.t_s) s += strf(" t=%.2f s", *v.t_s);
  if (v.where) s += strf(" at (%.2f, %.2f, %.2f)", v.where->x(), v.where->y(), v.where->z());
  return s + ": " + v.message;
}

void add_violation(Violations& out, ViolationKind kind, const std::string& uav, std::optional<double> t_s,
                   std::optional<Vec3> where, std::string message) {
  out.push_back({kind, uav, t_s, std::move(where), std::move(message)});
}

}  // namespace uavplan
