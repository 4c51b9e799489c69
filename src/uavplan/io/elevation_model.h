// Elevation models from files (contract: world.terrain {file}): any raster GDAL reads (GeoTIFF,
// SRTM .hgt, DTED, ASCII grid, ...) in its own coordinate system, placed in the scenario's local
// frame through its origin and resampled onto the world's terrain cells.
//
// Placement: each corner of the world's cells goes local -> WGS84 (GeoFrame) -> the raster's
// CRS (PROJ through GDAL, the best transformation available offline: for CH1903 / LV03 the
// published Helmert parameters, about 1 m) -> pixel. Heights are the band's values (with its
// scale and offset; metres, or feet converted) taken as metres above mean sea level in the
// origin's vertical datum: z = height - origin.alt (no geoid is applied, as for exports).
// Resampling: a cell's height is the highest pixel its footprint touches (the pixel box of its
// four corners), so the model never lowers the ground under a planner; the verifier and the
// planners see the same cells. Cells default to the raster's pixel on the ground (its smaller
// side), at most kMaxTerrainCells over the bounds (larger cells then). Pixels without data
// (NoData, NaN) are filled from their neighbours' highest, a ring at a time, and counted.
#pragma once

#include <optional>
#include <string>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/io/geo.h"
#include "uavplan/world/terrain.h"

namespace uavplan {

struct ElevationModel {
  TerrainGrid grid;
  ElevationSource source;
};

// Reads `path` and resamples it over the x, y of `bounds` (cells of `cell_m` when given). Throws
// InputError naming `file` (as the scenario wrote it) for a file GDAL cannot read, a raster
// without coordinate system or georeferencing, units that are not lengths, bounds that reach
// beyond the raster, or no height at all within them.
ElevationModel read_elevation_model(const std::string& path, const std::string& file, const GeoFrame& frame,
                                    const Aabb& bounds, std::optional<double> cell_m, std::size_t max_cells);

}  // namespace uavplan
