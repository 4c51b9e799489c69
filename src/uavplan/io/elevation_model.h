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

#include <cstdint>
#include <optional>
#include <string>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/stop.h"
#include "uavplan/io/geo.h"
#include "uavplan/world/terrain.h"

namespace uavplan {

// What one world may read of a model (docs/decisions/0019): about 10 s of reading on this
// project's machines; the window is read a strip of rows at a time (memory bounded whatever the
// window, the stop checked between strips).
inline constexpr std::uint64_t kMaxElevationPixels = 1ull << 31;
inline constexpr int kMaxElevationRowPixels = 1 << 22;

struct ElevationReadOptions {
  std::size_t max_cells = 1u << 24;     // cells over the bounds; larger cells past it
  std::size_t strip_bytes = 32u << 20;  // the window is read a strip of rows of at most this at a time
  StopCondition stop = {};              // its memory cap and deadline hold while reading
};

struct ElevationModel {
  TerrainGrid grid;
  ElevationSource source;
};

// Reads `path` and resamples it over the x, y of `bounds` (cells of `cell_m` when given). Throws
// InputError naming `file` (as the scenario wrote it) for a file GDAL cannot read, a raster
// without coordinate system or georeferencing, units that are not lengths, bounds that reach
// beyond the raster, no height at all within them, a geotransform or height that is not finite or
// beyond 1e9, a window past kMaxElevationPixels or the stop's memory cap (naming --max-memory).
// Throws Stopped when the options' stop holds between strips.
ElevationModel read_elevation_model(const std::string& path, const std::string& file, const GeoFrame& frame,
                                    const Aabb& bounds, std::optional<double> cell_m, const ElevationReadOptions& o);

}  // namespace uavplan
