// What every export shares: written precision, numbers in text, obstacle footprints and names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "uavplan/io/geo.h"
#include "uavplan/world/world.h"

namespace uavplan {

// Written precision: 1e-9 degrees (0.1 mm on the ground) and 0.1 mm, so files stay readable and
// identical across platforms while keeping far below any autopilot's resolution.
double round_deg(double v);
double round_m(double v);
LatLonAlt rounded(LatLonAlt g);
// The shortest text that reads back as v ("0" for -0).
std::string short_num(double v);

// Rows closer than this are one position (a hold); legs this parallel are one straight leg.
inline constexpr double kHoldMove_m = 1e-6;
inline constexpr double kCollinearCos = 1.0 - 1e-9;

// Horizontal footprint of an obstacle, counter-clockwise, not closed (circles as 64-gons).
std::vector<Vec2> footprint(const Obstacle& o);
// The scenario's id of obstacle k, else "obstacle K"; the same for radars.
std::string obstacle_name(const World& world, std::size_t k);
std::string radar_name(const World& world, std::size_t k);

}  // namespace uavplan
