#include "uavplan/io/export.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "uavplan/io/files.h"
#include "uavplan/io/gis_export.h"
#include "uavplan/io/qgc_export.h"

namespace uavplan {
namespace {

// The files the folder's manifest lists: plain names only, so nothing outside it is touched.
std::vector<std::string> manifest(const std::string& dir) {
  std::ifstream in(std::filesystem::path(dir) / kExportManifest);
  std::vector<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line == "." || line == ".." || line.find('/') != std::string::npos ||
        line.find('\\') != std::string::npos || line.find('\0') != std::string::npos)
      continue;
    names.push_back(line);
  }
  return names;
}

void remove_listed(const std::string& dir, const std::vector<std::string>& names, const std::set<std::string>& keep) {
  namespace fs = std::filesystem;
  for (const std::string& n : names) {
    if (keep.count(n)) continue;
    const fs::path p = fs::path(dir) / n;
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(p, ec))) fs::remove(p, ec);
  }
}

}  // namespace

std::optional<ExportFormat> export_format_from_string(std::string_view s) {
  for (ExportFormat f : {ExportFormat::qgc, ExportFormat::wpl, ExportFormat::geojson, ExportFormat::kml, ExportFormat::csv})
    if (to_string(f) == s) return f;
  return std::nullopt;
}

std::string_view to_string(ExportFormat f) {
  switch (f) {
    case ExportFormat::qgc: return "qgc";
    case ExportFormat::wpl: return "wpl";
    case ExportFormat::geojson: return "geojson";
    case ExportFormat::kml: return "kml";
    case ExportFormat::csv: return "csv";
  }
  return "?";
}

bool needs_origin(ExportFormat f) { return f != ExportFormat::csv; }

ExportOptions export_options(std::string_view firmware, std::string_view vehicle, std::string_view end,
                             std::string_view fence) {
  const auto bad = [](const char* what, std::string_view v, const char* choices) {
    return ExportError(std::string(what) + ": '" + std::string(v) + "' is not one of " + choices);
  };
  ExportOptions o;
  if (firmware == "ardupilot") o.firmware = Firmware::ardupilot;
  else if (firmware != "px4") throw bad("firmware", firmware, "px4, ardupilot");
  if (vehicle == "fixedwing") o.vehicle = VehicleKind::fixed_wing;
  else if (vehicle != "multirotor") throw bad("vehicle", vehicle, "multirotor, fixedwing");
  if (end == "rtl") o.end = MissionEnd::rtl;
  else if (end == "loiter") o.end = MissionEnd::loiter;
  else if (end == "none") o.end = MissionEnd::none;
  else if (end != "land") throw bad("end", end, "land, rtl, loiter, none");
  if (fence == "none") o.fence = FenceMode::none;
  else if (fence == "all") o.fence = FenceMode::all;
  else if (fence != "bounds") throw bad("fence", fence, "none, bounds, all");
  return o;
}

std::string file_stem(std::string_view id) {
  std::string s(id);
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  if (s.empty() || s[0] == '.') s.insert(s.begin(), '_');
  return s;
}

std::vector<ExportFile> export_files(const Scenario& sc, const VerifiedExport& flights, ExportFormat format,
                                     const ExportOptions& opt, std::vector<std::string>* notes) {
  if (needs_origin(format) && !sc.origin)
    throw ExportError("scenario '" + sc.name + "' has no origin: add origin: {lat, lon, alt} to export to WGS84");
  std::vector<ExportFile> files;
  switch (format) {
    case ExportFormat::geojson: files.push_back({"plan.geojson", plan_geojson(sc, flights)}); break;
    case ExportFormat::kml: files.push_back({"plan.kml", plan_kml(sc, flights)}); break;
    default: {
      std::vector<std::string> used;
      for (const ExportedUav& e : flights.uavs) {
        std::string stem = file_stem(e.spec->id);
        if (std::find(used.begin(), used.end(), stem) != used.end()) stem += "_" + std::to_string(used.size());
        used.push_back(stem);
        if (format == ExportFormat::qgc) {
          std::vector<std::string> mine;
          files.push_back({stem + ".plan", qgc_plan_json(sc, e, opt, &mine)});
          if (notes)
            for (const std::string& n : mine) notes->push_back(stem + ".plan: " + n);
        }
        if (format == ExportFormat::wpl) files.push_back({stem + ".waypoints", qgc_wpl(sc, e, opt)});
        if (format == ExportFormat::csv) files.push_back({stem + ".csv", trajectory_csv(sc, e)});
      }
    }
  }
  return files;
}

void write_export(const std::string& dir, const std::vector<ExportFile>& files) {
  std::set<std::string> names;
  std::string list = "# files of the last uavplan export in this folder (the next one removes them)\n";
  for (const ExportFile& f : files) {
    names.insert(f.name);
    list += f.name + "\n";
  }
  remove_listed(dir, manifest(dir), names);
  for (const ExportFile& f : files) write_file_atomic(dir + "/" + f.name, f.content);
  write_file_atomic(dir + "/" + kExportManifest, list);
}

void clear_export(const std::string& dir) {
  const std::vector<std::string> old = manifest(dir);
  if (old.empty()) return;
  remove_listed(dir, old, {});
  std::error_code ec;
  std::filesystem::remove(std::filesystem::path(dir) / kExportManifest, ec);
}

}  // namespace uavplan
