// Exports of a plan for the tools operators fly and look at: QGroundControl .plan, QGC WPL 110
// (MAVLink mission text), GeoJSON (RFC 7946), KML and CSV. Local ENU coordinates go to WGS84
// through the scenario's `origin` (GeoFrame); without one only CSV (local coordinates) exports.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/coordination/plan.h"
#include "uavplan/coordination/scenario.h"

namespace uavplan {

enum class ExportFormat { qgc, wpl, geojson, kml, csv };
std::optional<ExportFormat> export_format_from_string(std::string_view s);
std::string_view to_string(ExportFormat f);
// Whether the format is in WGS84 (needs the scenario's origin); CSV is local without one.
bool needs_origin(ExportFormat f);

enum class Firmware { px4, ardupilot };             // QGC firmwareType 12 / 3
enum class VehicleKind { multirotor, fixed_wing };  // MAV_TYPE 2 / 1
enum class MissionEnd { land, rtl, none };          // MAV_CMD_NAV_LAND (21) / RETURN_TO_LAUNCH (20)

struct ExportOptions {
  Firmware firmware = Firmware::px4;
  VehicleKind vehicle = VehicleKind::multirotor;
  MissionEnd end = MissionEnd::land;
  // Trajectory legs whose speeds differ by less than this fraction fly at one speed (no 178 item).
  double speed_change_fraction = 0.01;
};

// Thrown when a plan cannot be exported (no origin, a plan UAV unknown to the scenario).
class ExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// MAVLink commands the missions use.
inline constexpr int kCmdWaypoint = 16, kCmdLoiterTurns = 18, kCmdLoiterTime = 19, kCmdReturn = 20,
                     kCmdLand = 21, kCmdTakeoff = 22, kCmdChangeSpeed = 178;
inline constexpr int kFrameGlobal = 0, kFrameGlobalRelativeAlt = 3;

// One mission item as MAVLink carries it: params 5-7 are lat, lon (degrees) and altitude.
struct MissionItem {
  int command = kCmdWaypoint;
  int frame = kFrameGlobalRelativeAlt;
  std::array<double, 7> params{};
};

// The mission a UAV flies, read off its verified trajectory: takeoff at the start, a loiter
// where the trajectory holds still (MAV_CMD_NAV_LOITER_TIME, the hold's seconds), a waypoint at
// every change of direction, a speed change (178) before a leg whose speed differs, then land
// or return. Altitudes are relative to home (the start, on the origin's datum).
std::vector<MissionItem> mission_items(const Scenario& sc, const UavPlan& uav, const ExportOptions& opt);

struct ExportFile {
  std::string name;  // file name inside the output directory
  std::string content;
};

// Every file of one format: qgc, wpl and csv give one file per UAV with a trajectory (named by
// its id), geojson and kml one file for the whole plan. Throws ExportError.
std::vector<ExportFile> export_plan(const Scenario& sc, const Plan& plan, ExportFormat format,
                                    const ExportOptions& opt = {});

std::string qgc_plan_json(const Scenario& sc, const UavPlan& uav, const ExportOptions& opt);
std::string qgc_wpl(const Scenario& sc, const UavPlan& uav, const ExportOptions& opt);
std::string plan_geojson(const Scenario& sc, const Plan& plan);
std::string plan_kml(const Scenario& sc, const Plan& plan);
std::string trajectory_csv(const Scenario& sc, const UavPlan& uav);

// A UAV id made safe as a file name ([A-Za-z0-9_.-], others become '_').
std::string file_stem(std::string_view id);

}  // namespace uavplan
