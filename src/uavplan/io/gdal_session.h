// GDAL as this process uses it (docs/decisions/0019): a scenario's file is data, so GDAL may
// read only what the scenario names and nothing it could be steered to. At first use the process
// keeps only the drivers it reads with (rasters: GTiff, AAIGrid, SRTMHGT, DTED, EHdr, VRT;
// zones: KML, LIBKML; every other driver is deregistered, so no file, a VRT's source included,
// can be opened by another), every virtual file system but /vsimem/ answers "no such file"
// (/vsicurl/ and the other network ones, /vsistdin/, archives that could wrap them), PROJ's
// network is off, and GDAL's switches that read outside a file are set off (raw VRT bands, pixel
// functions in Python, LIBKML's external styles). Its messages are kept from the terminal while
// it reads (the library never prints), to be quoted in ours.
#pragma once

#include <gdal_priv.h>

#include <string>

namespace uavplan {

// GDAL's block cache (GDAL_CACHEMAX): a window is read once, a strip at a time, so a larger cache
// only holds memory past --max-memory (GDAL's default is 5 % of the machine's).
inline constexpr int kGdalCacheMiB = 64;

// What a file is opened as; each has its own drivers.
enum class GdalInput { elevation_model, kml_zones };

// Sets the policy above (once per process; thread-safe). Every open below calls it.
void register_gdal_drivers();

// Opens `path` read-only with the drivers allowed for `kind` only; null when none reads it.
GDALDatasetUniquePtr open_gdal(const std::string& path, GdalInput kind);

// The drivers allowed for `kind`, e.g. "GTiff, AAIGrid, ..." (for messages and docs).
std::string gdal_drivers_text(GdalInput kind);

// While alive, GDAL's errors on this thread go to no handler that prints; gdal_said() quotes the
// last one.
class QuietGdal {
 public:
  QuietGdal();
  ~QuietGdal();
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
};

// " (GDAL: <its last message>)", or empty when it said nothing.
std::string gdal_said();

}  // namespace uavplan
