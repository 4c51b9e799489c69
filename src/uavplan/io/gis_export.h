// GIS and spreadsheet files of an export: GeoJSON (RFC 7946: lon, lat, alt; counter-clockwise
// closed rings), KML (absolute altitudes, extruded obstacle footprints) and CSV (t, x, y, z,
// with lat, lon, alt when the scenario has an origin). Routes are the exported flights, their
// added legs included; obstacles and radar threats carry the scenario's ids.
#pragma once

#include <string>

#include "uavplan/io/flight_export.h"

namespace uavplan {

std::string plan_geojson(const Scenario& scenario, const VerifiedExport& flights);
std::string plan_kml(const Scenario& scenario, const VerifiedExport& flights);
std::string trajectory_csv(const Scenario& scenario, const ExportedUav& uav);

}  // namespace uavplan
