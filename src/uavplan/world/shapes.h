// Hard obstacles: a route may never come closer to them than the UAV's radius.
#pragma once

#include <limits>
#include <string_view>
#include <variant>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

struct Sphere {
  Vec3 center;
  double radius_m = 0.0;
};

// Vertical cylinder (no-fly zone, electromagnetic zone).
struct Cylinder {
  Vec2 center;
  double radius_m = 0.0;
  double z_min_m = 0.0, z_max_m = 0.0;
};

struct Box {
  Vec3 min, max;
};

// Extruded footprint (building); the polygon may be non-convex, given in either orientation.
struct Prism {
  std::vector<Vec2> polygon;
  double z_min_m = 0.0, z_max_m = 0.0;
};

using Obstacle = std::variant<Sphere, Cylinder, Box, Prism>;

Aabb bounding_box(const Obstacle& o);

// Euclidean distance from p to the solid (0 inside or on it).
double point_distance(const Obstacle& o, const Vec3& p);
// "sphere", "cylinder", "box" or "prism": the scenario file's word for the shape.
std::string_view shape_name(const Obstacle& o);

// The point of the solid nearest to p (p itself when inside).
Vec3 closest_point(const Obstacle& o, const Vec3& p);

// Exact distance from segment [a, b] to the solid (0 when they meet). Where a bound shows the
// distance is at least `cap`, that bound (>= cap) is returned instead: callers that keep the
// smaller of the two lose nothing, and long segments far from a solid cost a few operations.
double segment_distance(const Obstacle& o, const Vec3& a, const Vec3& b,
                        double cap = std::numeric_limits<double>::infinity());

}  // namespace uavplan
