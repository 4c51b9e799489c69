// Every file that reading an elevation model will open, checked before GDAL opens any
// (docs/decisions/0019). A scenario is a file from anyone: it may name its raster, and that
// raster may name others (a VRT's sources), but none of them may make the tool read a file the
// scenario was not pointed at, wait on a FIFO, or read raw bytes as heights.
//  - each file: a regular file (links followed), not empty, at most kMaxRasterFileBytes; a link
//    inside the scenario's folder may not lead out of it (the scenario names the folder it
//    leaves openly, as "../data/dem.tif", or not at all);
//  - beside each file, nothing that GDAL may open as a sidecar (a name beginning with the file's
//    stem: .aux.xml, .ovr, .hdr, .prj, ...) is a FIFO, device or socket;
//  - a VRT: plain bands of simple or complex sources only (no raw bands, no pixel functions, no
//    warped or pansharpened datasets, no open options), each source a relative path
//    (relativeToVRT="1") without "..", ':' or markup, inside the first VRT's folder, and checked
//    like the file itself (a VRT source that is a VRT is checked in turn, kMaxVrtDepth deep).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace uavplan {

inline constexpr std::uint64_t kMaxRasterFileBytes = 8ull << 30;  // a raster file (read by window)
inline constexpr int kMaxVrtDepth = 4;                            // VRTs naming VRTs

// Throws InputError naming `label` (the scenario's path of the file), the file refused, the
// source that names it and why.
void check_elevation_files(const std::filesystem::path& path, const std::filesystem::path& scenario_folder,
                           const std::string& label);

}  // namespace uavplan
