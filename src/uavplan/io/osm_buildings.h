// Building footprints from GeoJSON (OpenStreetMap extracts) as prism obstacles in the
// scenario's local frame. Heights follow OSM's tagging: `height` (metres, or a string with a
// unit), else `building:levels` (+ `roof:levels`) times a level height, else a default;
// `min_height` / `building:min_level` lift the base of a building part.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/io/geo.h"
#include "uavplan/world/shapes.h"

namespace uavplan {

struct BuildingOptions {
  // Storey height for `building:levels`: 3 m, the value OSM's Simple 3D Buildings guidance
  // and common renderers assume for a level.
  double level_height_m = 3.0;
  // A footprint with neither a height nor levels: 10 m (about three storeys), chosen high
  // rather than low because an underestimate lets a route clip a roof.
  double default_height_m = 10.0;
  double base_z_m = 0.0;  // z of the ground the heights stand on (the local frame's z = 0)
};

struct BuildingCounts {
  int from_height = 0, from_levels = 0, defaulted = 0;
  int skipped = 0;  // features that are not areas (points, lines) or have no area
};

// Parses an OSM length: "12", "12.5 m", "12 metres", "40 ft", "40'", "12'6\"". Metres out;
// nullopt for anything else (OSM's guidance: the unit is metres unless one is given).
std::optional<double> parse_osm_length_m(std::string_view text);

// Every Polygon / MultiPolygon feature of a GeoJSON FeatureCollection (RFC 7946: lon, lat
// in WGS84), its outer ring projected through `frame`. Inner rings (courtyards) are filled:
// a prism has no holes, and filling errs on the safe side. Throws InputError naming `file`
// and the feature for malformed input.
std::vector<Prism> buildings_from_geojson(const std::string& text, const std::string& file, const GeoFrame& frame,
                                          const BuildingOptions& options, BuildingCounts* counts = nullptr);

}  // namespace uavplan
