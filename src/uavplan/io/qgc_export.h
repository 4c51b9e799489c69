// QGroundControl's files of one exported UAV: the .plan (JSON: mission, geofence, rally point)
// and the WPL 110 text (MAVLink mission rows), both from mission_items().
// The .plan follows what QGroundControl itself writes: items with a position carry Altitude,
// AltitudeMode and AMSLAltAboveTerrain; DO commands and the return are frame 2 without them.
// Geofence (--fence): `none`; `bounds` (default): the world's bounds as the inclusion polygon
// and, as exclusions, at most max_fence_exclusions of the obstacles the UAV can neither over-
// nor under-fly at the heights it flies, the largest footprints first (autopilots cap stored
// fence points: PX4 about 256 vertices, ArduPilot FENCE_TOTAL); `all`: every such exclusion.
#pragma once

#include <string>
#include <vector>

#include "uavplan/io/flight_export.h"

namespace uavplan {

// `notes` receives what the user should know (exclusions dropped from the fence).
std::string qgc_plan_json(const Scenario& scenario, const ExportedUav& uav, const ExportOptions& options,
                          std::vector<std::string>* notes = nullptr);
std::string qgc_wpl(const Scenario& scenario, const ExportedUav& uav, const ExportOptions& options);

}  // namespace uavplan
