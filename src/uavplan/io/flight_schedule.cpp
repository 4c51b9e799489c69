#include "uavplan/io/flight_schedule.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace uavplan {
namespace {

// A multirotor leg as ArduCopter flies it: the horizontal at the commanded speed, the vertical
// within its climb and descent speeds, whichever takes longer.
double copter_leg_s(const Vec3& a, const Vec3& b, double speed_mps, const CopterVerticalSpeeds& v) {
  const double dz = b.z() - a.z();
  const double vertical_s = dz > 0.0 ? dz / v.up_mps : -dz / v.down_mps;
  return std::max((b - a).head<2>().norm() / std::max(speed_mps, 0.1), vertical_s);
}

// Up to the next 10 cm/s, 10 % over what is needed.
double with_room_mps(double needed_mps) { return std::ceil(needed_mps * 1.1 * 10.0 - 1e-9) / 10.0; }

// ArduPlane (4.7): its airspeed range the UAV's as equivalent airspeed over the flight's
// altitudes (it ignores a DO_CHANGE_SPEED outside AIRSPEED_MIN..AIRSPEED_MAX, in m/s: the least
// where the air is thinnest, the most where it is densest), its cruise at home's; RTL_AUTOLAND 2
// where the mission lands on a runway (it refuses to arm a mission holding DO_LAND_START without
// it; 2: a return flies the landing sequence).
std::vector<std::pair<std::string, double>> arduplane_parameters(const ExportedUav& e, double origin_amsl_m) {
  const SpeedLimits& v = e.spec->speed;
  double low = e.home.z(), high = e.home.z();
  for (const TrajectorySample& s : e.plan.trajectory) low = std::min(low, s.p.z()), high = std::max(high, s.p.z());
  const auto eas = [&](double tas_mps, double z_m) {
    return tas_mps * equivalent_per_true_airspeed(origin_amsl_m + z_m);
  };
  std::vector<std::pair<std::string, double>> p = {
      {"AIRSPEED_MIN", std::floor(eas(v.min_mps, high))},
      {"AIRSPEED_CRUISE", std::round(eas(v.cruise_mps, e.home.z()) * 100.0) / 100.0},
      {"AIRSPEED_MAX", std::ceil(eas(v.max_mps, low))}};
  if (e.end == MissionEnd::land) p.emplace_back("RTL_AUTOLAND", 2.0);
  return p;
}

}  // namespace

double equivalent_per_true_airspeed(double alt_amsl_m) {
  // ISA troposphere: rho / rho0 = (1 - L h / T0)^(g / (R L) - 1), L h / T0 = 2.25577e-5 h.
  constexpr double kLapsePerT0_per_m = 2.25577e-5, kDensityExponent = 4.2559, kTropopause_m = 11000.0;
  const double h = std::clamp(alt_amsl_m, -1000.0, kTropopause_m);
  return std::pow(1.0 - kLapsePerT0_per_m * h, 0.5 * kDensityExponent);
}

bool arducopter_timing(const ExportOptions& opt) {
  return opt.firmware == Firmware::ardupilot && opt.vehicle == VehicleKind::multirotor;
}

CopterVerticalSpeeds copter_vertical_speeds(const ExportedUav& e) {
  CopterVerticalSpeeds v;
  const Trajectory& tr = e.plan.trajectory;
  for (std::size_t k = e.body_begin + 1; k <= std::min(e.body_end, tr.size() - 1); ++k) {
    const double dt = tr[k].t_s - tr[k - 1].t_s, dz = tr[k].p.z() - tr[k - 1].p.z();
    if (dt <= 0.0) continue;
    if (dz > 0.0) v.up_mps = std::max(v.up_mps, with_room_mps(dz / dt));
    if (dz < 0.0) v.down_mps = std::max(v.down_mps, with_room_mps(-dz / dt));
  }
  return v;
}

double copter_ramp_lag_s(double speed_mps) {
  const double v = std::max(speed_mps, 0.0), a = kCopterAccel_mps2, j = kCopterJerk_mps3;
  // Symmetric acceleration profile: the distance is v T / 2, so the lag behind speed v is T / 2.
  const double ramp_s = v <= a * a / j ? 2.0 * std::sqrt(v / j) : v / a + a / j;
  return 0.5 * ramp_s;
}

double copter_speed_change_leg_m(double speed_mps) {
  constexpr double kLeastLeg_m = 25.0, kLeastLeg_s = 5.0;
  return std::max(kLeastLeg_m, kLeastLeg_s * speed_mps);
}

namespace {

// The time the autopilot takes from a mission's start to the top of its take-off and on to
// where the plan's rows begin (an airborne start), or to the top of the take-off in the plan;
// `vertical`: ArduCopter's climb and descent speeds for it.
double modelled_takeoff_s(const ExportedUav& e, const ExportOptions& opt, const CopterVerticalSpeeds& vertical) {
  const Trajectory& tr = e.plan.trajectory;
  if (!arducopter_timing(opt)) {  // the export's timing: its rows at cruise speed
    if (!e.takeoff_before) return 0.0;
    return tr.front().t_s - exported_rows(e).front().t_s;
  }
  const double cruise_mps = e.spec->speed.cruise_mps;
  // From rest at the top of the climb: the pause there and the ramp to speed on the route's first
  // leg (started that much earlier, it is at speed on the plan's clock).
  const double from_rest_s = kCopterWaypointPause_s + copter_ramp_lag_s(cruise_mps);
  double s =
      kCopterLiftoff_s + copter_leg_s(e.home, e.takeoff_to, cruise_mps, vertical) + kCopterClimbRamps_s + from_rest_s;
  if (e.takeoff_before) s += copter_leg_s(e.takeoff_to, tr.front().p, cruise_mps, vertical);
  return s;
}

}  // namespace

std::vector<ScheduledStart> flight_schedule(const Scenario& sc, const VerifiedExport& flights,
                                            const ExportOptions& opt) {
  std::vector<ScheduledStart> out;
  for (const ExportedUav& e : flights.uavs) {
    const Trajectory& tr = e.plan.trajectory;
    if (tr.empty()) continue;
    ScheduledStart s;
    s.id = e.spec->id;
    const CopterVerticalSpeeds v = copter_vertical_speeds(e);
    const double takeoff_s = modelled_takeoff_s(e, opt, v);
    if (e.takeoff_before) {
      s.start_s = tr.front().t_s - takeoff_s;
    } else {  // the plan's own climb from departure_s to the top: started earlier by the difference
      const double planned_s = tr[std::min(e.body_begin, tr.size() - 1)].t_s - e.departure_s;
      s.start_s = e.departure_s - std::max(0.0, takeoff_s - planned_s);
    }
    s.flight_s = tr.back().t_s - s.start_s;
    if (arducopter_timing(opt)) {
      s.parameters = {{"WPNAV_SPEED_UP", std::round(v.up_mps * 100.0)},
                      {"WPNAV_SPEED_DN", std::round(v.down_mps * 100.0)},
                      {"WPNAV_ACCEL", kCopterAccel_mps2 * 100.0},
                      {"WPNAV_ACCEL_Z", kCopterAccelZ_mps2 * 100.0},
                      {"WPNAV_JERK", kCopterJerk_mps3},
                      // The landing's descent at ArduCopter's default, not at a steep route's.
                      {"LAND_SPEED_HIGH", std::round(kCopterDescent_mps * 100.0)}};
    }
    if (opt.firmware == Firmware::ardupilot && opt.vehicle == VehicleKind::fixed_wing)
      s.parameters = arduplane_parameters(e, sc.origin ? sc.origin->alt_m : 0.0);
    s.vehicle = opt.vehicle;
    out.push_back(s);
  }
  return out;
}

std::string schedule_json(const std::vector<ScheduledStart>& schedule,
                          const std::vector<std::pair<std::string, std::string>>& files_by_uav) {
  nlohmann::json uavs = nlohmann::json::array();
  for (const ScheduledStart& s : schedule) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& [uav, file] : files_by_uav)
      if (uav == s.id) files.push_back(file);
    nlohmann::json uav = {{"id", s.id},
                          {"vehicle", s.vehicle == VehicleKind::fixed_wing ? "fixed_wing" : "multirotor"},
                          {"start_s", s.start_s},
                          {"flight_s", s.flight_s},
                          {"files", files}};
    if (!s.parameters.empty()) {
      uav["parameters"] = nlohmann::json::object();
      for (const auto& [name, value] : s.parameters) uav["parameters"][name] = value;
    }
    uavs.push_back(std::move(uav));
  }
  const nlohmann::json j = {
      {"clock",
       "the plan's: start each mission (arm it in AUTO) at start_s on one clock common to all; its take-off is "
       "included; set each UAV's parameters on its vehicle first (the timing assumes them)"},
      {"uavs", uavs}};
  return j.dump(2) + "\n";
}

ExportFile schedule_file(const std::vector<ScheduledStart>& schedule, const std::vector<ExportFile>& files) {
  std::vector<std::pair<std::string, std::string>> by_uav;
  for (const ExportFile& f : files)
    if (!f.uav.empty()) by_uav.emplace_back(f.uav, f.name);
  return {"schedule.json", schedule_json(schedule, by_uav), ""};
}

}  // namespace uavplan
