#include "uavplan/io/export.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "uavplan/core/text.h"
#include "uavplan/io/files.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/gis_export.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/mission_items.h"
#include "uavplan/io/qgc_export.h"

namespace uavplan {
namespace {

// The files the folder's manifest lists, each with the fingerprint of what this tool wrote
// there: plain names only, so nothing outside the folder is touched. A line without a
// fingerprint (a hand-written manifest) names nothing this tool may remove.
struct Listed {
  std::string name, fingerprint, uav;
};
struct Manifest {
  std::string source;  // the fingerprint of what the files were made from ("" in older manifests)
  std::vector<Listed> files;
};
constexpr std::string_view kSourceLine = "#source\t";

Manifest manifest(const std::string& dir) {
  std::ifstream in(std::filesystem::path(dir) / kExportManifest);
  Manifest m;
  std::vector<Listed>& listed = m.files;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(kSourceLine, 0) == 0) m.source = line.substr(kSourceLine.size(), 16);
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    const auto tab2 = line.find('\t', tab + 1);
    Listed l{line.substr(0, tab), line.substr(tab + 1, 16), tab2 == std::string::npos ? "" : line.substr(tab2 + 1)};
    if (l.name.empty() || l.name == "." || l.name == ".." || l.name.find('/') != std::string::npos ||
        l.name.find('\\') != std::string::npos || l.name.find('\0') != std::string::npos || l.fingerprint.size() != 16)
      continue;
    listed.push_back(std::move(l));
  }
  return m;
}

// Whether the listed file still holds exactly what this tool wrote (not edited or replaced since,
// not a name the manifest was made to name).
bool holds_what_was_written(const std::string& dir, const Listed& l) {
  namespace fs = std::filesystem;
  const fs::path p = fs::path(dir) / l.name;
  std::error_code ec;
  if (l.name == kExportManifest || !fs::is_regular_file(fs::symlink_status(p, ec))) return false;
  try {
    return content_fingerprint(read_text_file(p.string())) == l.fingerprint;
  } catch (const std::exception&) {
    return false;
  }
}

// Removes the listed files not in `keep` that still hold what this tool wrote; returns them.
std::vector<std::string> remove_listed(const std::string& dir, const std::vector<Listed>& listed,
                                       const std::set<std::string>& keep) {
  std::vector<std::string> removed;
  for (const Listed& l : listed) {
    if (keep.count(l.name) || !holds_what_was_written(dir, l)) continue;
    std::error_code ec;
    if (std::filesystem::remove(std::filesystem::path(dir) / l.name, ec)) removed.push_back(l.name);
  }
  return removed;
}

// The format a file of an export is in, by its name (export_files names them).
std::string_view format_of(std::string_view name) {
  const auto ends = [&](std::string_view e) {
    return name.size() >= e.size() && name.substr(name.size() - e.size()) == e;
  };
  if (ends(".plan")) return "qgc";
  if (ends(".waypoints")) return "wpl";
  if (ends(".geojson")) return "geojson";
  if (ends(".kml")) return "kml";
  if (ends(".csv")) return "csv";
  return "";
}

// A file name no other UAV's has: the id made safe, cut to a length every file system takes,
// and numbered where that is taken already (compared without case: some file systems ignore it).
std::string unique_stem(std::string_view id, std::set<std::string>& taken_lower) {
  const std::string base = file_stem(id);
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  std::string stem = base;
  for (int n = 2; taken_lower.count(lower(stem)); ++n) stem = base + "_" + std::to_string(n);
  taken_lower.insert(lower(stem));
  return stem;
}

}  // namespace

std::optional<ExportFormat> export_format_from_string(std::string_view s) {
  for (ExportFormat f :
       {ExportFormat::qgc, ExportFormat::wpl, ExportFormat::geojson, ExportFormat::kml, ExportFormat::csv})
    if (to_string(f) == s) return f;
  return std::nullopt;
}

std::string_view to_string(ExportFormat f) {
  switch (f) {
    case ExportFormat::qgc:
      return "qgc";
    case ExportFormat::wpl:
      return "wpl";
    case ExportFormat::geojson:
      return "geojson";
    case ExportFormat::kml:
      return "kml";
    case ExportFormat::csv:
      return "csv";
  }
  return "?";
}

bool needs_origin(ExportFormat f) { return f != ExportFormat::csv; }
bool autopilot_format(ExportFormat f) { return f == ExportFormat::qgc || f == ExportFormat::wpl; }
std::string_view default_vehicle(const Scenario& sc) { return sc.mission.airfield ? "fixedwing" : "multirotor"; }

std::optional<std::string> export_request_problem(const Scenario& sc, const std::vector<ExportFormat>& formats,
                                                  const ExportOptions& opt) {
  if (sc.mission.airfield && opt.vehicle == VehicleKind::multirotor)
    return "a formation_mission takes off and lands on its runway, as a fixed wing does: export it with --vehicle "
           "fixedwing (the default for it)";
  for (const ExportFormat f : formats)
    if (needs_origin(f) && !sc.origin)
      return "scenario '" + sc.name + "' has no origin: add origin: {lat, lon, alt} to export " +
             std::string(to_string(f)) + " (WGS84); csv exports local coordinates without one";
  if (!opt.autopilot) return std::nullopt;
  try {  // an altitude frame the firmware does not take
    (void)altitude_frame(sc, opt);
  } catch (const ExportError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

ExportOptions export_options(std::string_view firmware, std::string_view vehicle, std::string_view end,
                             std::string_view fence) {
  const auto bad = [](const char* what, std::string_view v, const char* choices) {
    return ExportError(std::string(what) + ": '" + std::string(v) + "' is not one of " + choices);
  };
  ExportOptions o;
  if (firmware == "ardupilot")
    o.firmware = Firmware::ardupilot;
  else if (firmware != "px4")
    throw bad("firmware", firmware, "px4, ardupilot");
  if (vehicle == "fixedwing")
    o.vehicle = VehicleKind::fixed_wing;
  else if (vehicle != "multirotor")
    throw bad("vehicle", vehicle, "multirotor, fixedwing");
  if (end == "rtl")
    o.end = MissionEnd::rtl;
  else if (end == "loiter")
    o.end = MissionEnd::loiter;
  else if (end == "none")
    o.end = MissionEnd::none;
  else if (end != "land")
    throw bad("end", end, "land, rtl, loiter, none");
  if (fence == "none")
    o.fence = FenceMode::none;
  else if (fence == "all")
    o.fence = FenceMode::all;
  else if (fence != "bounds")
    throw bad("fence", fence, "none, bounds, all");
  return o;
}

std::string file_stem(std::string_view id) {
  constexpr std::size_t kMaxStem = 100;  // with its extension and a number, far below NAME_MAX (255)
  std::string s(id.substr(0, std::min(id.size(), kMaxStem)));
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
    case ExportFormat::geojson:
      files.push_back({"plan.geojson", plan_geojson(sc, flights), ""});
      break;
    case ExportFormat::kml:
      files.push_back({"plan.kml", plan_kml(sc, flights), ""});
      break;
    default: {
      std::set<std::string> taken;
      for (const ExportedUav& e : flights.uavs) {
        const std::string stem = unique_stem(e.spec->id, taken);
        const std::string& id = e.spec->id;
        if (format == ExportFormat::qgc) {
          std::vector<std::string> mine;
          files.push_back({stem + ".plan", qgc_plan_json(sc, e, opt, &mine), id});
          if (notes)
            for (const std::string& n : mine) notes->push_back(std::string(stem).append(".plan: ").append(n));
        }
        if (format == ExportFormat::wpl) files.push_back({stem + ".waypoints", qgc_wpl(sc, e, opt), id});
        if (format == ExportFormat::csv) files.push_back({stem + ".csv", trajectory_csv(sc, e), id});
      }
    }
  }
  return files;
}

std::vector<std::string> frame_notes(const Scenario& sc, const VerifiedExport& flights) {
  constexpr double kNotedShrink = 1e-3;
  double far_m = 0.0;
  for (const ExportedUav& e : flights.uavs)
    for (const TrajectorySample& row : e.plan.trajectory) far_m = std::max(far_m, row.p.head<2>().norm());
  const double shrink = far_m * far_m * kGroundShrinkPerRange2;
  if (!sc.origin || shrink < kNotedShrink) return {};
  return {"the flights reach " + num_text(std::round(far_m / 1000.0)) +
          " km from the origin: on the ground, distances across the bearing from it are up to " +
          num_text(std::round(shrink * 1e4) / 100.0) +
          " % shorter than planned (azimuthal equidistant frame; distances from the origin are exact)"};
}

ExportReplaced write_export(const std::string& dir, const std::vector<ExportFile>& files,
                            const std::vector<ExportFile>& with, const std::string& source) {
  std::set<std::string> names, formats;
  std::string list =
      "# files of the uavplan exports in this folder: name, fingerprint, UAV (the next export of\n"
      "# another source, or of their format, removes those that still hold what was written)\n";
  if (!source.empty()) list += std::string(kSourceLine) + source + "\n";
  StagedFiles staged(dir);
  for (const ExportFile& f : files) {
    if (!names.insert(f.name).second) throw std::logic_error("export file " + f.name + " written twice");
    formats.insert(std::string(format_of(f.name)));
    staged.add(f.name, f.content);
    list += f.name + "\t" + content_fingerprint(f.content) + "\t" + printable(f.uav) + "\n";
  }
  const Manifest old = manifest(dir);  // read before the new one replaces it
  ExportReplaced out;
  std::set<std::string> keep = names;
  if (!source.empty() && old.source == source)  // the same source: the other formats stay
    for (const Listed& l : old.files)
      if (!keep.count(l.name) && !formats.count(std::string(format_of(l.name))) && holds_what_was_written(dir, l)) {
        keep.insert(l.name);
        out.kept.push_back(l.name);
        list += l.name + "\t" + l.fingerprint + "\t" + l.uav + "\n";
      }
  for (const ExportFile& f : with) staged.add(f.name, f.content);
  staged.add(kExportManifest, list);
  staged.commit();
  out.removed = remove_listed(dir, old.files, keep);
  return out;
}

void clear_export(const std::string& dir) {
  const std::vector<Listed> old = manifest(dir).files;
  if (old.empty()) return;
  remove_listed(dir, old, {});
  std::error_code ec;
  std::filesystem::remove(std::filesystem::path(dir) / kExportManifest, ec);
}

std::optional<std::string> altitude_note(const Scenario& sc, const ExportOptions& opt) {
  const std::string model = sc.elevation ? "the elevation model " + printable(sc.elevation->file) : "the terrain";
  switch (altitude_frame(sc, opt)) {
    case AltitudeFrame::amsl:
      return "mission altitudes are above mean sea level (MAV_FRAME_GLOBAL, QGC's AMSL mode): the verified heights "
             "over " +
             model + ", whatever terrain data the autopilot holds";
    case AltitudeFrame::terrain:
      return "mission altitudes are above the terrain of " + model +
             " at each item (MAV_FRAME_GLOBAL_TERRAIN_ALT): ArduPilot follows its own terrain data between and at "
             "items, so its heights differ from the verified ones where that data differs; --altitude amsl flies "
             "the verified heights";
    default:
      return std::nullopt;
  }
}

}  // namespace uavplan
