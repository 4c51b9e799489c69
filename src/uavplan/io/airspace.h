// No-fly zones and fences from the files operators have (contract: world.airspace), as
// obstacles in the scenario's local frame:
//  - GeoJSON (RFC 7946, WGS84 lon/lat): every Polygon / MultiPolygon's outer ring is an exclusion
//    zone; properties floor_m and ceiling_m (metres above mean sea level) bound it in height,
//    else it spans every height;
//  - a QGroundControl plan's geoFence: exclusion polygons (prisms) and circles (cylinders) over
//    every height; one inclusion zone (polygon, or circle as the 64-gon inscribed in it) bounds
//    the world: the bounds shrink to its box and the rest of that box is closed by prisms.
//  - KML (through GDAL's LIBKML / KML drivers): every Placemark's Polygon and MultiGeometry's
//    polygons, read as GeoJSON's (ExtendedData floor_m / ceiling_m bound a zone in height).
// Every zone is also kept as the file gave it (FenceZone, WGS84) for the exports' fence.
#pragma once

#include <string>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/vec.h"
#include "uavplan/io/geo.h"
#include "uavplan/world/shapes.h"

namespace uavplan {

struct Airspace {
  std::vector<Obstacle> zones;        // exclusion zones and what lies outside the inclusion zone
  std::vector<std::string> zone_ids;  // per zone: "FILE zone 3", "FILE outside the fence"
  std::optional<Aabb> inclusion_box;  // the inclusion zone's box (x, y), when the file has one
  std::vector<FenceZone> fence;       // the zones as read; obstacles index into `zones`
};

// Reads one airspace file by its extension (.geojson / .json, .plan). `bounds` gives the heights
// a zone without floor or ceiling spans. Throws InputError naming `file` and the place for a
// malformed file, a zone that crosses itself, more than one inclusion zone.
Airspace read_airspace(const std::string& text, const std::string& file, const GeoFrame& frame, const Aabb& bounds);

}  // namespace uavplan
