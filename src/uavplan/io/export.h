// Exports of a plan for the tools operators fly and look at: QGroundControl .plan, QGC WPL 110
// (MAVLink mission text), GeoJSON (RFC 7946), KML and CSV. Only what holds leaves the tool:
// verified_export() (flight_export.h) picks the UAVs that hold and adds the legs their mission
// files fly; the files are written from that. Local ENU coordinates go to WGS84 through the
// scenario's `origin` (geo.h); without one only CSV (local coordinates) exports.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/io/flight_export.h"

namespace uavplan {

enum class ExportFormat { qgc, wpl, geojson, kml, csv };
std::optional<ExportFormat> export_format_from_string(std::string_view s);
std::string_view to_string(ExportFormat f);
// Export options from the command line's spellings: firmware px4 | ardupilot, vehicle
// multirotor | fixedwing, end land | rtl | loiter | none, fence none | bounds | all. Throws
// ExportError naming the value that is none of them.
ExportOptions export_options(std::string_view firmware, std::string_view vehicle, std::string_view end,
                             std::string_view fence);

// Whether the format is in WGS84 (needs the scenario's origin); CSV is local without one.
bool needs_origin(ExportFormat f);
// An autopilot's mission file (qgc, wpl): ExportOptions::autopilot.
bool autopilot_format(ExportFormat f);
// The vehicle exported when none is named: "fixedwing" for a formation_mission (it flies from a
// runway), else "multirotor".
std::string_view default_vehicle(const Scenario& scenario);

// Why this export cannot be made of the scenario, asked before a plan is made or exported (the
// command line and the Python module alike): a runway mission as a multirotor, a WGS84 format
// without an origin, an altitude frame the firmware does not take; nullopt when it can.
std::optional<std::string> export_request_problem(const Scenario& scenario, const std::vector<ExportFormat>& formats,
                                                  const ExportOptions& options);

struct ExportFile {
  std::string name;  // file name inside the output directory
  std::string content;
  std::string uav;  // the UAV whose mission it is; empty for a file of the whole plan
};

// Every file of one format: qgc, wpl and csv one per exported UAV (named by its id made safe,
// cut to 100 characters and numbered where another UAV's file has that name already: distinct by
// construction, even where the file system ignores case), geojson and kml one for the whole plan. `notes` receives what the user should
// know (fence zones dropped). Throws ExportError without an origin for a WGS84 format.
std::vector<ExportFile> export_files(const Scenario& scenario, const VerifiedExport& flights, ExportFormat format,
                                     const ExportOptions& options = {}, std::vector<std::string>* notes = nullptr);

// What the WGS84 frame does to the verified distances where the flights reach far from the
// origin (geo.h): a line when ground distances across the bearing shrink by 0.1 % or more.
std::vector<std::string> frame_notes(const Scenario& scenario, const VerifiedExport& flights);
// What the mission files' altitudes are measured from, where not home (the firmware's frame and
// what the autopilot follows between items).
std::optional<std::string> altitude_note(const Scenario& scenario, const ExportOptions& options);

// A UAV id made safe as a file name ([A-Za-z0-9_.-], others become '_'; at most 100 characters).
std::string file_stem(std::string_view id);

// The export folder keeps a manifest (.uavplan-export) of the files the exports wrote, each with
// the fingerprint of its content and its UAV, and the fingerprint of what they were made from
// (`source`: the scenario, the plan and the export options). A new export of the same source
// keeps the files of the formats it does not write (formats exported one at a time add up); of
// another source, or for the formats it writes, it removes those it does not write again (a UAV
// left out this time) that still hold what was written: a folder never mixes two plans and no
// file this tool did not write is removed. The export is all or nothing (files.h: StagedFiles):
// every file, `with` (plan.json of `plan --export`) and the manifest go to temporaries first; a
// failure leaves the folder as it was. Throws OutputError. clear_export() removes the last
// export's files (a new plan makes them stale).
inline constexpr const char* kExportManifest = ".uavplan-export";
struct ExportReplaced {
  std::vector<std::string> kept;     // files of an earlier export of the same source, other formats
  std::vector<std::string> removed;  // files of the last export this one does not write again
};
ExportReplaced write_export(const std::string& dir, const std::vector<ExportFile>& files,
                            const std::vector<ExportFile>& with = {}, const std::string& source = "");
void clear_export(const std::string& dir);

}  // namespace uavplan
