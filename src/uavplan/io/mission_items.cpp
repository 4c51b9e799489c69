#include "uavplan/io/mission_items.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "uavplan/core/text.h"
#include "uavplan/io/export_common.h"
#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

// Compass yaw (0 = north, clockwise) of a horizontal direction, degrees in [0, 360).
double compass_yaw_deg(const Vec3& d) {
  if (std::hypot(d.x(), d.y()) < 1e-12) return 0.0;
  double yaw = std::atan2(d.x(), d.y()) * 180.0 / std::numbers::pi;
  if (yaw < 0.0) yaw += 360.0;
  return yaw;
}

class Items {
 public:
  Items(const GeoFrame& frame, double home_amsl_m, const ExportOptions& opt, AltitudeFrame altitude, const World& world)
      : frame_(frame),
        home_amsl_m_(home_amsl_m),
        at_amsl_m_(home_amsl_m),
        opt_(opt),
        altitude_(altitude),
        world_(world) {}

  void at(int command, const Vec3& p, std::array<double, 4> head) {
    const LatLonAlt g = frame_.to_wgs84(p);
    MissionItem it;
    it.command = command;
    it.frame = mav_frame(altitude_);
    it.amsl_m = round_m(g.alt_m);
    const double alt = altitude_ == AltitudeFrame::amsl      ? g.alt_m
                       : altitude_ == AltitudeFrame::terrain ? p.z() - world_.ground_z(p.x(), p.y())
                                                             : g.alt_m - home_amsl_m_;
    it.params = {round_m(head[0]),     round_m(head[1]),     round_m(head[2]), round_m(head[3]),
                 round_deg(g.lat_deg), round_deg(g.lon_deg), round_m(alt)};
    items_.push_back(it);
    at_amsl_m_ = g.alt_m;
  }
  void command(int command, std::array<double, 4> head = {}) {
    MissionItem it;
    it.command = command;
    it.frame = kFrameMission;
    it.params = {round_m(head[0]), round_m(head[1]), round_m(head[2]), round_m(head[3]), 0, 0, 0};
    items_.push_back(it);
  }
  // A DO_CHANGE_SPEED before the first leg (the vehicle's own default speed is not the plan's)
  // and wherever the leg from `a` to `b` in `dt_s` needs another (see speed_drift_s). Fixed
  // wing: airspeed (speed type 0, as QGroundControl writes it; ArduPlane's type 1 only sets a
  // minimum ground speed), the equivalent airspeed of the planned ground speed in still air
  // (command_speed); multirotor: ground
  // speed (type 1), along the leg, but ArduCopter's is horizontal (WPNAV_SPEED: a leg's climb or
  // descent comes on top). Throttle unchanged (-1).
  void speed(const Vec3& a, const Vec3& b, double dt_s) {
    const double len_m = arducopter_timing(opt_) ? (b - a).head<2>().norm() : (b - a).norm();
    if (len_m < 1e-3 || dt_s <= 0.0) return;  // straight up or down: flown at the climb speeds
    const double v = len_m / dt_s, fraction = opt_.speed_change_fraction;
    if (speed_mps_ > 0.0 && std::abs(v - speed_mps_) < fraction * speed_mps_) {
      const double drift_s = drift_s_ + len_m / speed_mps_ - dt_s;
      if (std::abs(drift_s) <= opt_.speed_drift_s) {
        drift_s_ = drift_s;
        return;
      }
    }
    // The leg's speed, paying back the drift so far within the fraction (0.9 of it: the checks'
    // tolerance is the fraction of the commanded speed).
    const double pay_back = len_m / std::max(dt_s - drift_s_, 1e-9);
    const double mps = std::clamp(std::min(pay_back, std::max(v, max_speed_mps_)), v * (1.0 - 0.9 * fraction),
                                  v * (1.0 + 0.9 * fraction));
    command_speed(mps);
    drift_s_ += len_m / mps - dt_s;
  }
  void set_max_speed(double mps) { max_speed_mps_ = mps; }
  // A hold of hold_s where the plan stops between legs at v_in and v_out: ArduCopter stops and
  // starts on its S-curves (and rests on the waypoint), so it loiters that much less; what the
  // hold cannot take is time lost. Elsewhere (the first hold: the schedule times the start) and
  // for the others, the hold as planned.
  double flown_hold_s(double hold_s, bool first, double v_in_mps, double v_out_mps) {
    if (first || !arducopter_timing(opt_)) return hold_s;
    const double lost_s = copter_ramp_lag_s(v_in_mps) + kCopterWaypointPause_s + copter_ramp_lag_s(v_out_mps);
    drift_s_ += std::max(0.0, lost_s - hold_s);
    return std::max(0.0, hold_s - lost_s);
  }
  // Cruise speed on legs off the plan's clock (to a start beside the take-off, home again).
  void cruise(double mps) {
    if (speed_mps_ <= 0.0 || std::abs(mps - speed_mps_) >= opt_.speed_change_fraction * speed_mps_) command_speed(mps);
  }
  // `mps` true; a fixed wing's airspeed commanded as the equivalent airspeed the firmware holds
  // (at the altitude of the waypoint the leg starts from).
  void command_speed(double mps) {
    const bool wing = opt_.vehicle == VehicleKind::fixed_wing;
    command(kCmdChangeSpeed, {wing ? 0.0 : 1.0, wing ? mps * equivalent_per_true_airspeed(at_amsl_m_) : mps, -1.0, 0});
    speed_mps_ = mps;
  }
  // Rows [from, to] of the trajectory: holds, straight legs, speed changes.
  void body(const Trajectory& tr, std::size_t from, std::size_t to) {
    std::size_t i = from;
    while (i < to) {
      const Vec3 a = tr[i].p;
      if ((tr[i + 1].p - a).norm() <= kHoldMove_m) {
        const std::size_t held_from = i;
        double hold_s = 0.0;  // consecutive holds are one loiter
        while (i < to && (tr[i + 1].p - tr[i].p).norm() <= kHoldMove_m) {
          hold_s += tr[i + 1].t_s - tr[i].t_s;
          ++i;
        }
        if (hold_s > 0.0) {
          const double v_out = i + 1 <= to && i + 1 < tr.size()
                                   ? (tr[i + 1].p - tr[i].p).norm() / std::max(tr[i + 1].t_s - tr[i].t_s, 1e-12)
                                   : 0.0;
          at(kCmdLoiterTime, a, {flown_hold_s(hold_s, held_from == from, speed_mps_, v_out), 0, 0, 0});
        }
        continue;
      }
      // One straight leg at one speed, as long as the following legs keep direction and speed.
      const Vec3 dir = (tr[i + 1].p - a).normalized();
      const double v = (tr[i + 1].p - a).norm() / std::max(tr[i + 1].t_s - tr[i].t_s, 1e-12);
      std::size_t j = i + 1;
      while (j < to) {
        const Vec3 d = tr[j + 1].p - tr[j].p;
        const double len = d.norm();
        if (len <= kHoldMove_m) break;
        const double vj = len / std::max(tr[j + 1].t_s - tr[j].t_s, 1e-12);
        if (d.dot(dir) / len < kCollinearCos || std::abs(vj - v) > opt_.speed_change_fraction * v) break;
        ++j;
      }
      // Commanded: the mean speed of the legs flown as one (what the leg's timing needs).
      speed(a, tr[j].p, tr[j].t_s - tr[i].t_s);
      at(kCmdWaypoint, tr[j].p, {0, 0, 0, compass_yaw_deg(dir)});
      i = j;
    }
  }
  std::vector<MissionItem>& items() { return items_; }

 private:
  const GeoFrame& frame_;
  double home_amsl_m_;
  double at_amsl_m_;            // the last positioned item's altitude above sea level
  double speed_mps_ = 0.0;      // commanded so far, true speed (0: none yet)
  double drift_s_ = 0.0;        // time lost (> 0) or gained on the plan's clock by the legs so far
  double max_speed_mps_ = 0.0;  // no speed paying drift back goes over it (nor the leg's own)
  const ExportOptions& opt_;
  AltitudeFrame altitude_;
  const World& world_;
  std::vector<MissionItem> items_;
};

}  // namespace

AltitudeFrame altitude_frame(const Scenario& sc, const ExportOptions& opt) {
  if (opt.altitude == AltitudeFrame::terrain && opt.firmware == Firmware::px4)
    throw ExportError(
        "--altitude terrain: PX4 takes no mission item above the terrain (MAV_FRAME_GLOBAL_TERRAIN_ALT is "
        "ArduPilot's); --altitude amsl flies the same verified heights above sea level");
  if (opt.altitude != AltitudeFrame::standard) return opt.altitude;
  return sc.elevation ? AltitudeFrame::amsl : AltitudeFrame::home;
}

int mav_frame(AltitudeFrame frame) {
  switch (frame) {
    case AltitudeFrame::amsl:
      return kFrameGlobal;
    case AltitudeFrame::terrain:
      return kFrameGlobalTerrainAlt;
    default:
      return kFrameGlobalRelativeAlt;
  }
}

std::vector<MissionItem> mission_items(const Scenario& sc, const ExportedUav& e, const ExportOptions& opt) {
  if (!sc.origin)
    throw ExportError("scenario '" + sc.name + "' has no origin: add origin: {lat, lon, alt} to export to WGS84");
  // A flight at ground level (a flat world's plan) has no take-off an autopilot accepts (PX4:
  // "Takeoff altitude below home altitude").
  constexpr double kLeastTakeoff_m = 0.1;
  if (e.takeoff_to.z() - e.home.z() < kLeastTakeoff_m)
    throw ExportError("UAV '" + printable(e.spec->id) + "' flies at ground level (its take-off climbs " +
                      num_text(e.takeoff_to.z() - e.home.z()) +
                      " m): an autopilot refuses a take-off to its home's altitude; plan it in a world with height "
                      "and a start above the ground, or export csv, geojson or kml");
  const GeoFrame frame(*sc.origin);
  const Trajectory& tr = e.plan.trajectory;
  const double cruise = e.spec->speed.cruise_mps;
  Items m(frame, frame.to_wgs84(e.home).alt_m, opt, altitude_frame(sc, opt), sc.world);
  m.set_max_speed(e.spec->speed.max_mps);
  const Vec3 first = tr[std::min(e.body_begin + 1, tr.size() - 1)].p - tr[e.body_begin].p;
  // Fixed wing: param1 is the minimum pitch of the climb-out (ArduPlane climbs at it, else at a
  // few degrees; PX4 takes it as the minimum pitch too): the climb that was verified.
  const double pitch_deg = opt.vehicle == VehicleKind::fixed_wing
                               ? std::min(kFixedWingClimbOut_deg, e.spec->max_climb_rad * 180.0 / std::numbers::pi)
                               : 0.0;
  m.at(kCmdTakeoff, e.takeoff_to, {pitch_deg, 0, 0, compass_yaw_deg(first)});
  if ((tr[e.body_begin].p - e.takeoff_to).norm() > kHoldMove_m) {  // a take-off beside the start
    m.cruise(cruise);
    m.at(kCmdWaypoint, tr[e.body_begin].p, {0, 0, 0, compass_yaw_deg(tr[e.body_begin].p - e.takeoff_to)});
  }
  m.body(tr, e.body_begin, e.body_end);
  switch (e.end) {
    case MissionEnd::land:
      if (e.approach) {  // PX4's landing pattern: the marker, the approach waypoint, the touch-down
        auto& items = m.items();
        for (auto it = items.rbegin(); it != items.rend(); ++it)
          if (it->command == kCmdWaypoint) {
            MissionItem start;
            start.command = kCmdLandStart;
            start.frame = kFrameMission;
            items.insert(it.base() - 1, start);
            break;
          }
      }
      m.at(kCmdLand, *e.touchdown, {0, 0, 0, 0});
      break;
    case MissionEnd::rtl: {
      m.cruise(cruise);
      Vec3 from = tr[e.body_end].p;
      for (const Vec3& p : e.return_points) {
        m.at(kCmdWaypoint, p, {0, 0, 0, compass_yaw_deg(p - from)});
        from = p;
      }
      m.command(kCmdReturn);
      break;
    }
    case MissionEnd::loiter:
      m.at(kCmdLoiterUnlimited, tr[e.body_end].p, {0, 0, e.loiter_radius_m, 0});
      break;
    case MissionEnd::none:
      break;
  }
  return std::move(m.items());
}

}  // namespace uavplan
