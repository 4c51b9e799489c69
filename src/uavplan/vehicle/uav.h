// A UAV's identity, mission endpoints and limits, and the route-geometry checks they imply.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "uavplan/core/units.h"
#include "uavplan/core/vec.h"
#include "uavplan/vehicle/autopilot_params.h"

namespace uavplan {

struct SpeedLimits {
  double min_mps = 0.0;
  double cruise_mps = 5.0;
  double max_mps = 5.0;
};

struct UavSpec {
  std::string id;
  Vec3 start = Vec3::Zero();
  std::optional<Vec3> goal;
  // On the ground: where it takes off and lands when that is neither its start nor its goal (its
  // flight: home, up, start, ..., goal, back, down).
  std::optional<Vec3> home;
  std::optional<double> heading_rad;  // initial yaw, 0 = east, pi/2 = north
  double radius_m = 0.5;              // obstacles are inflated by it
  double clearance_m = 0.0;           // extra distance kept from obstacles and terrain
  double min_agl_m = 0.0;             // least height above the ground (but taking off and landing)
  bool min_agl_given = false;         // the scenario sets min_agl (else planners may keep a default)
  std::optional<double> max_agl_m;    // most height above the ground (terrain following), as min_agl
  SpeedLimits speed;
  double max_turn_rad = kPi;        // heading change between consecutive segments
  double max_climb_rad = kPi / 2;   // |pitch| of any segment
  std::optional<double> ceiling_m;  // highest altitude allowed, below the world's top
  // Moving obstacles and other UAVs are known to it only within this range, sensed every
  // mission step; absent: moving obstacles are known in advance.
  std::optional<double> sensor_range_m;
  // Rate limits of a vehicle flown through a model (contract: max_turn_rate_deg_s, max_climb_rate).
  std::optional<double> max_turn_rate_rad_s;
  std::optional<double> max_climb_rate_mps;
  // P5 eq. 1's autopilot model (`model: {type: autopilot, ...}`); none: a point mass.
  std::optional<AutopilotParams> model;
};

// The distance a UAV keeps from obstacles and terrain: its radius and the clearance asked for.
inline double keep_off_m(const UavSpec& u) { return u.radius_m + u.clearance_m; }

// Tolerance of every angle check: routes are built to the limit, floating error must not fail them.
inline constexpr double kAngleTolerance_rad = 1e-7;

// Pitch of a segment, atan2(dz, horizontal length); 0 for a zero-length segment.
double pitch_rad(const Vec3& segment);

// The turn between consecutive segment directions: the larger of the 3-D angle between them
// (P4's constraint) and the change of horizontal heading (the contract's "heading change"),
// the latter only when both segments have a horizontal part.
double turn_rad(const Vec3& from, const Vec3& to);
// turn_rad(from, to) <= limit_rad (below pi), by cosines: no acos or atan2 (a planner's inner loop).
bool turn_within(const Vec3& from, const Vec3& to, double limit_rad);

// Unit horizontal vector of a heading.
inline Vec3 heading_vector(double heading_rad) { return {std::cos(heading_rad), std::sin(heading_rad), 0.0}; }

struct LimitViolation {
  enum class Kind { turn, climb } kind;
  std::size_t index;  // turn: the waypoint where it turns (0 = against the start heading); climb: segment
  double value_rad;
};

// Checks the turn limit at every interior waypoint (and at the start against the start heading,
// when there is one) and the climb limit on every segment; zero-length segments are skipped.
std::vector<LimitViolation> check_route_limits(std::span<const Vec3> waypoints, const UavSpec& uav);

}  // namespace uavplan
