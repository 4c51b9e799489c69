#include "uavplan/io/flight_export.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/mission.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/ground_legs.h"
#include "uavplan/io/export_common.h"
#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/mission_items.h"

namespace uavplan {
namespace {

constexpr double kSampleDt_s = 1.0;  // rows of the added legs, at most this far apart
constexpr double kTurnStep_s = 2.0;  // a turn back flies legs this long (at cruise speed)
constexpr double kClearTolerance_m = 1e-6;
// A blocked vertical take-off is tried from rings around the start (Builder::beside).
constexpr int kBesideSteps = 10, kBesideDirections = 16;

// `pts` flown at v_mps from the last row; only rows after it, so that time strictly increases
// (interpolators need it): time_route also writes the hold up to the departure, and a point
// where the UAV already is takes no time.
void append_flight(Trajectory& tr, const std::vector<Vec3>& pts, double v_mps) {
  std::vector<Vec3> w{tr.back().p};
  w.insert(w.end(), pts.begin(), pts.end());
  const double from_s = tr.back().t_s;
  for (const TrajectorySample& row : time_route(w, v_mps, from_s, kSampleDt_s))
    if (row.t_s > from_s) tr.push_back(row);
}

// A multirotor's landing: level to above `down`, then down to it, at cruise speed; an ArduCopter
// mission's descent as NAV_LAND flies it (LAND_SPEED_HIGH, the descent speed schedule.json asks
// for, to LAND_ALT_LOW above the touch-down, then LAND_SPEED), so that the UAVs still flying are
// verified against the landing that is flown (at cruise speed a 60 m descent took 7.5 s of the 53
// ArduCopter takes).
void append_landing(Trajectory& tr, const Vec3& top, const Vec3& down, double cruise_mps, bool arducopter) {
  if (!arducopter) {
    append_flight(tr, {top, down}, cruise_mps);
    return;
  }
  append_flight(tr, {top}, cruise_mps);
  const Vec3 low(down.x(), down.y(), std::min(top.z(), down.z() + kCopterLandAltLow_m));
  append_flight(tr, {low}, kCopterDescent_mps);
  append_flight(tr, {down}, kCopterLandSpeed_mps);
}

// Horizontal unit direction of the last leg that moves horizontally, else of the heading, else east.
Vec3 final_heading(const Trajectory& tr, std::size_t last, const UavSpec& u) {
  for (std::size_t k = last; k > 0; --k) {
    const Vec3 d(tr[k].p.x() - tr[k - 1].p.x(), tr[k].p.y() - tr[k - 1].p.y(), 0.0);
    if (d.norm() > kSamePoint_m) return d.normalized();
  }
  return u.heading_rad ? heading_vector(*u.heading_rad) : Vec3::UnitX();
}

Vec3 first_heading(const Trajectory& tr, const UavSpec& u) {
  if (u.heading_rad) return heading_vector(*u.heading_rad);
  for (std::size_t k = 1; k < tr.size(); ++k) {
    const Vec3 d(tr[k].p.x() - tr[0].p.x(), tr[k].p.y() - tr[0].p.y(), 0.0);
    if (d.norm() > kSamePoint_m) return d.normalized();
  }
  return Vec3::UnitX();
}

Vec3 rotated(const Vec3& d, double a) {
  return Vec3(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y(), 0.0);
}

double signed_angle(const Vec3& from, const Vec3& to) {
  return std::atan2(from.x() * to.y() - from.y() * to.x(), from.x() * to.x() + from.y() * to.y());
}

// A straight leg to or from the ground at height ground_z: why it is not clear, or empty.
std::string leg_problem(const World& w, const Vec3& a, const Vec3& b, double keep, double ground_z,
                        const std::string& what) {
  if (!w.in_bounds(a) || !w.in_bounds(b)) {
    const auto outside = [&](const Vec3& p) {
      return (w.bounds().min - p).cwiseMax(p - w.bounds().max).cwiseMax(Vec3::Zero()).norm();
    };
    return what + " leaves the world bounds by " + num_text(std::ceil(std::max(outside(a), outside(b)))) + " m";
  }
  const double c = w.ground_leg_clearance(a, b, keep, ground_z);
  if (c >= keep - kClearTolerance_m) return {};
  return what + " comes within " + num_text(c) + " m of an obstacle or the terrain (radius plus clearance " +
         num_text(keep) + " m)";
}

// Where a straight glide (or climb) at `angle_rad` from `air` along `dir` meets the ground.
Vec3 ground_along(const World& w, const Vec3& air, const Vec3& dir, double angle_rad) {
  double g = w.ground_z(air.x(), air.y()), d = 0.0;
  for (int k = 0; k < 4; ++k) {  // the ground under the far end decides the length
    d = std::max(0.0, air.z() - g) / std::tan(angle_rad);
    g = w.ground_z(air.x() + d * dir.x(), air.y() + d * dir.y());
  }
  return Vec3(air.x() + d * dir.x(), air.y() + d * dir.y(), g);
}

class Builder {
 public:
  Builder(const Scenario& sc, const ExportOptions& opt) : w_(sc.world), airfield_(sc.mission.airfield), opt_(opt) {}

  // The UAV's exported flight, or why it cannot be. Without an autopilot's file, a flight whose
  // added legs cannot be flown is the plan's as it is (`note` says why).
  std::string build(const UavSpec& u, const UavPlan& up, ExportedUav& e, std::string& note) const {
    e.spec = &u;
    e.plan = up;
    const GroundLegs legs = ground_legs(w_, up.trajectory);
    const bool runway = airfield_ && legs.takeoff && legs.landing;
    std::string why = runway ? runway_flight(legs, e) : takeoff(u, legs, e);
    if (why.empty() && !runway) why = ending(u, legs, e);
    if (why.empty() || opt_.autopilot) return why;
    note = why;
    e = ExportedUav{};  // as planned: no legs added
    e.spec = &u;
    e.plan = up;
    e.home = e.takeoff_to = up.trajectory.front().p;
    e.body_end = up.trajectory.size() - 1;
    return {};
  }

 private:
  // A formation_mission's flight from the runway to the runway (P5): the autopilot's take-off
  // from the threshold, lined up (the taxi to it is the ground crew's), climbing out along the
  // runway until above it (contract: kAirborneAbove_m); the route; its landing pattern from
  // where the straight final glide begins to the touch-down, then the roll-out.
  std::string runway_flight(const GroundLegs& legs, ExportedUav& e) const {
    if (!fixed_wing())
      return "a formation_mission UAV takes off and lands on the runway, as a fixed wing does: export it with "
             "--vehicle fixedwing";
    const Trajectory& tr = e.plan.trajectory;
    const Airfield& af = *airfield_;
    std::size_t roll = 0;  // lined up at the threshold, the last row there before lift-off
    for (std::size_t k = 0; k < legs.takeoff_end; ++k)
      if ((tr[k].p - af.position).norm() <= kClearTolerance_m) roll = k;
    std::size_t top = roll;
    while (top + 1 < tr.size() && tr[top].p.z() <= af.position.z() + kAirborneAbove_m) ++top;
    std::size_t touch = legs.landing_begin;
    while (touch + 1 < tr.size() && !w_.on_ground(tr[touch].p)) ++touch;
    std::size_t approach = touch - 1;  // back along the straight final glide
    const Vec3 glide = (tr[touch].p - tr[approach].p).normalized();
    while (approach > top + 1 && (tr[approach].p - tr[approach - 1].p).normalized().dot(glide) > kCollinearCos)
      --approach;
    const Vec3 final_leg = tr[touch].p - tr[approach].p;
    const double glide_deg = rad_to_deg(std::atan2(-final_leg.z(), final_leg.head<2>().norm()));
    if (glide_deg > kFixedWingGlideFlown_deg)
      return "its final glide of " + num_text(glide_deg) + " deg is steeper than PX4's FW_LND_ANG " +
             num_text(kFixedWingGlide_deg) + " deg";
    e.home = tr[roll].p;
    e.takeoff_to = tr[top].p;
    e.body_begin = top;
    e.body_end = approach;
    e.end = MissionEnd::land;
    e.approach = tr[approach].p;
    e.touchdown = tr[touch].p;
    e.departure_s = tr[roll].t_s;
    return {};
  }

  bool fixed_wing() const { return opt_.vehicle == VehicleKind::fixed_wing; }

  bool flat() const { return w_.bounds().max.z() - w_.bounds().min.z() <= kClearTolerance_m; }

  std::string takeoff(const UavSpec& u, const GroundLegs& legs, ExportedUav& e) const {
    if (flat() && fixed_wing())
      return "a flat (2-D) world's plan is exported for multirotors: a fixed wing's climb-out and glide need room "
             "the plan's plane does not hold";
    const Trajectory& tr = e.plan.trajectory;
    if (legs.takeoff) {
      if (fixed_wing())
        return "a fixed-wing UAV cannot fly its planned vertical take-off: give it an airborne start (its climb-out is "
               "checked) or export it as a multirotor";
      e.home = tr.front().p;
      e.body_begin = legs.takeoff_end;
      e.takeoff_to = tr[legs.takeoff_end].p;
      for (std::size_t k = 0; k < legs.takeoff_end && tr[k].p == e.home; ++k)
        e.departure_s = tr[k].t_s;  // the climb's start
      return {};
    }
    e.takeoff_to = tr.front().p;
    e.takeoff_before = true;
    return fixed_wing() ? climb_out(u, e) : vertical_takeoff(u, e);
  }

  // A multirotor's take-off below its airborne start, else beside it.
  std::string vertical_takeoff(const UavSpec& u, ExportedUav& e) const {
    const Vec3 s = e.plan.trajectory.front().p;
    const double keep = keep_off_m(u);
    e.home = Vec3(s.x(), s.y(), w_.ground_z(s.x(), s.y()));
    const std::string why = leg_problem(w_, e.home, s, keep, e.home.z(), "its take-off straight up to its start");
    if (why.empty()) return {};
    const auto spot = clear_column_beside(s, keep);
    if (!spot)
      return why + ", and so does one from any spot within " + num_text(kBesideSteps * beside_step_m(keep)) + " m";
    e.takeoff_to = spot->first;
    e.home = spot->second;
    return {};
  }

  // A multirotor's landing straight down from its goal, else level to the nearest clear spot on
  // rings around it and down there (NAV_LAND flies to its position at the height it has, then
  // descends: sloped ground, a terrain step beside the goal).
  std::string vertical_landing(const UavSpec& u, ExportedUav& e) const {
    Trajectory& tr = e.plan.trajectory;
    const Vec3 f = tr.back().p;
    const double keep = keep_off_m(u);
    Vec3 top = f, down(f.x(), f.y(), w_.ground_z(f.x(), f.y()));
    const std::string why = leg_problem(w_, f, down, keep, down.z(), "its landing straight down from its goal");
    if (!why.empty()) {
      const auto spot = clear_column_beside(f, keep);
      if (!spot)
        return why + ", and so does one at any spot within " + num_text(kBesideSteps * beside_step_m(keep)) + " m";
      top = spot->first;
      down = spot->second;
    }
    e.touchdown = down;
    append_landing(tr, top, down, u.speed.cruise_mps, arducopter_timing(opt_));
    return {};
  }

  // A fixed wing's climb-out into its airborne start's heading, else turned by up to what the turn
  // limit allows (the turn at the start within it).
  std::string climb_out(const UavSpec& u, ExportedUav& e) const {
    const Vec3 s = e.plan.trajectory.front().p;
    const double climb = std::min(u.max_climb_rad, deg_to_rad(kFixedWingClimbOut_deg));
    const Vec3 head = first_heading(e.plan.trajectory, u);
    // The largest turn in the plane whose 3-D angle with the climb is within the limit.
    const double most = std::acos(std::min(1.0, std::cos(std::min(u.max_turn_rad, kPi / 2)) / std::cos(climb)));
    std::string first;
    for (const double a : {0.0, 0.5, -0.5, 1.0, -1.0}) {
      const Vec3 home = ground_along(w_, s, -rotated(head, a * most), climb);
      const std::string why = leg_problem(w_, home, s, keep_off_m(u), home.z(),
                                          "its climb-out to its start (" + num_text(rad_to_deg(climb)) + " deg over " +
                                              num_text(std::round((s - home).head<2>().norm())) + " m)");
      if (why.empty()) {
        e.home = home;
        return {};
      }
      if (first.empty()) first = why;
    }
    return first + ", and so does one turned by up to its turn limit";
  }

  // Where a multirotor whose column under `s` is blocked (sloped ground, an overhang, an obstacle
  // beside it) goes up or down instead: the nearest clear column on rings around s, with a clear
  // level leg between its top (at s's height) and s. Returns (top, ground); none when none is clear.
  std::optional<std::pair<Vec3, Vec3>> clear_column_beside(const Vec3& s, double keep) const {
    const double below = w_.bounds().min.z() - 1.0;  // the level leg keeps off the ground too
    for (int ring = 1; ring <= kBesideSteps; ++ring)
      for (int k = 0; k < kBesideDirections; ++k) {
        const double r = ring * beside_step_m(keep), a = 2.0 * kPi * k / kBesideDirections;
        const double x = s.x() + r * std::cos(a), y = s.y() + r * std::sin(a);
        const Vec3 ground(x, y, w_.ground_z(x, y)), top(x, y, s.z());
        if (top.z() < ground.z() + keep || !leg_problem(w_, ground, top, keep, ground.z(), "").empty() ||
            !leg_problem(w_, top, s, keep, below, "").empty())
          continue;
        return std::pair{top, ground};
      }
    return std::nullopt;
  }
  static double beside_step_m(double keep) { return std::max(2.0 * keep, 1.0); }

  std::string ending(const UavSpec& u, const GroundLegs& legs, ExportedUav& e) const {
    Trajectory& tr = e.plan.trajectory;
    e.body_end = tr.size() - 1;
    if (legs.landing) {  // the plan lands at its goal: that is its end, whatever --end says
      if (fixed_wing())
        return "a fixed-wing UAV cannot fly its planned vertical landing: give it a goal in the air (the landing "
               "pattern "
               "follows it) or export it as a multirotor";
      e.end = MissionEnd::land;
      e.body_end = legs.landing_begin;
      e.touchdown = tr.back().p;
      return {};
    }
    e.end = opt_.end;
    switch (opt_.end) {
      case MissionEnd::none:
        return {};
      case MissionEnd::land:
        return fixed_wing() ? glide(u, e) : vertical_landing(u, e);
      case MissionEnd::loiter:
        if (!fixed_wing()) return {};
        e.loiter_radius_m = fixed_wing_loiter_radius_m(opt_.firmware);
        return circle_problem(u, tr.back().p, e.loiter_radius_m, "its loiter circle");
      case MissionEnd::rtl:
        return return_home(u, e);
    }
    return {};
  }

  // Fixed wing: a 4.9-degree glide straight on from the goal, else turned by up to the turn limit.
  std::string glide(const UavSpec& u, ExportedUav& e) const {
    Trajectory& tr = e.plan.trajectory;
    const Vec3 f = tr.back().p, dir = final_heading(tr, tr.size() - 1, u);
    const double turn = std::min(u.max_turn_rad, kPi / 2);
    std::string first;
    Vec3 last = dir;  // the last leg that moves, in 3-D
    for (std::size_t k = tr.size() - 1; k > 0; --k)
      if ((tr[k].p - tr[k - 1].p).norm() > kSamePoint_m) {
        last = (tr[k].p - tr[k - 1].p).normalized();
        break;
      }
    for (const double a : {0.0, 0.5 * turn, -0.5 * turn, turn, -turn}) {
      const Vec3 d = rotated(dir, a);
      const Vec3 t = ground_along(w_, f, d, deg_to_rad(kFixedWingGlideFlown_deg));
      // The turn into the glide is a 3-D angle: turned by the whole limit and pitched down, over it.
      if (std::acos(std::clamp(last.dot((t - f).normalized()), -1.0, 1.0)) > u.max_turn_rad) {
        if (first.empty()) first = "the turn into it is over the turn limit";
        continue;
      }
      const std::string why = leg_problem(w_, f, t, keep_off_m(u), t.z(), "the glide");
      if (why.empty()) {
        e.approach = f;
        e.touchdown = t;
        append_flight(tr, {t}, u.speed.cruise_mps);
        return {};
      }
      if (first.empty()) first = why;
    }
    return "no clear " + num_text(kFixedWingGlideFlown_deg) +
           "-degree landing glide from its goal within its turn limit (" + first +
           "): use --end loiter or --end rtl, or a goal with room ahead of it";
  }

  // Back within the turn limit, straight to above home at the goal's height, then down
  // (multirotor) or circling there (fixed wing).
  std::string return_home(const UavSpec& u, ExportedUav& e) const {
    Trajectory& tr = e.plan.trajectory;
    const Vec3 f = tr.back().p;
    const Vec3 above(e.home.x(), e.home.y(), f.z());
    const double v = u.speed.cruise_mps, turn = std::max(u.max_turn_rad, deg_to_rad(1.0));
    const double step = std::max(v * kTurnStep_s, 2.0 * keep_off_m(u));
    Vec3 p = f, dir = final_heading(tr, tr.size() - 1, u);
    for (int k = 0; k < 400; ++k) {  // turn towards home in steps of at most the turn limit
      const Vec3 to(above.x() - p.x(), above.y() - p.y(), 0.0);
      if (to.norm() <= step) break;
      const double a = signed_angle(dir, to.normalized());
      if (std::abs(a) <= turn) break;
      dir = rotated(dir, std::copysign(turn, a));
      p += step * dir;
      e.return_points.push_back(p);
    }
    e.return_points.push_back(above);
    append_flight(tr, e.return_points, v);
    if (!fixed_wing()) {
      append_flight(tr, {e.home}, v);
      return {};
    }
    e.loiter_radius_m = fixed_wing_loiter_radius_m(opt_.firmware);
    return circle_problem(u, above, e.loiter_radius_m, "its loiter circle above home");
  }

  // A fixed-wing circle of radius r around c: the ball of radius r plus its keep-off is clear.
  std::string circle_problem(const UavSpec& u, const Vec3& c, double r, const std::string& what) const {
    const double need = r + keep_off_m(u);
    if (!w_.bounds().contains(c + Vec3(need, need, 0)) || !w_.bounds().contains(c - Vec3(need, need, 0)))
      return what + " (" + num_text(r) + " m) leaves the world bounds";
    const double clear = w_.clearance(c, need);
    if (clear >= need - kClearTolerance_m) return {};
    return what + " (" + num_text(r) + " m) comes within " + num_text(clear - r) + " m of an obstacle or the terrain";
  }

  const World& w_;
  const std::optional<Airfield>& airfield_;
  const ExportOptions& opt_;
};

// Fixed-wing circles against the other UAVs: while one circles (from its arrival on), every
// other keeps its separation from the whole circle.
std::string circle_meets(const Scenario& sc, const ExportedUav& e, const std::vector<ExportedUav>& all) {
  if (e.loiter_radius_m <= 0.0) return {};
  const Vec3 c = e.plan.trajectory.back().p;
  const double t0 = e.plan.trajectory.back().t_s;
  for (const ExportedUav& o : all) {
    if (&o == &e) continue;
    const double need = required_separation_m(sc, *e.spec, *o.spec) + e.loiter_radius_m;
    const Trajectory& tr = o.plan.trajectory;
    for (std::size_t k = 0; k < tr.size(); ++k) {
      if (k + 1 < tr.size() && tr[k + 1].t_s < t0) continue;
      const Vec3& a = tr[k].p;
      const Vec3& b = k + 1 < tr.size() ? tr[k + 1].p : a;
      if (point_segment_distance(c, a, b) < need)
        return "its loiter circle (" + num_text(e.loiter_radius_m) + " m) is within the separation of " + o.spec->id +
               " at t=" + num_text(std::max(t0, tr[k].t_s)) + " s";
    }
  }
  return {};
}

// The exported UAVs' whole flights verified together: goals moved to where they now end.
std::vector<Violation> verify_flights(const Scenario& sc, const std::vector<ExportedUav>& uavs) {
  Scenario ext = sc;
  // Via points and lengths are the plan's, verified; a formation_mission keeps its airfield rule
  // (separation in the air only, a landed UAV gone).
  const Mission* mission = find_mission(ext.mission.type);
  if (!mission || mission->declaration().export_rules == ExportRules::independent) ext.mission.type = "independent";
  ext.mission.waypoints.clear();
  Plan p;
  for (const ExportedUav& e : uavs) {
    for (UavSpec& s : ext.uavs)
      if (s.id == e.spec->id) s.goal = e.plan.trajectory.back().p;
    p.uavs.push_back(e.plan);
  }
  std::vector<Violation> out;
  for (Violation& v : verify_plan(ext, p))
    if (v.kind != ViolationKind::not_planned) out.push_back(std::move(v));
  return out;
}

}  // namespace

std::string_view to_string(MissionEnd e) {
  switch (e) {
    case MissionEnd::land:
      return "land";
    case MissionEnd::rtl:
      return "rtl";
    case MissionEnd::loiter:
      return "loiter";
    case MissionEnd::none:
      return "none";
  }
  return "?";
}

double fixed_wing_loiter_radius_m(Firmware f) { return f == Firmware::px4 ? 80.0 : 60.0; }

namespace {

// Where the trajectory is at rows[k].t_s on the chord from rows[i] to rows[j].
double synchronised_distance(const Trajectory& tr, std::size_t i, std::size_t j, std::size_t k) {
  const double span = tr[j].t_s - tr[i].t_s;
  const double f = span > 0.0 ? (tr[k].t_s - tr[i].t_s) / span : 0.0;
  return (tr[k].p - (tr[i].p + f * (tr[j].p - tr[i].p))).norm();
}

// Douglas-Peucker on the rows [begin, end] with the synchronised distance; returns whether a row
// was left out.
bool simplify_body(ExportedUav& e, double tol_m) {
  Trajectory& tr = e.plan.trajectory;
  const std::size_t begin = e.body_begin, end = e.body_end;
  if (end <= begin + 1) return false;
  std::vector<char> keep(tr.size(), 1);
  std::fill(keep.begin() + static_cast<std::ptrdiff_t>(begin) + 1, keep.begin() + static_cast<std::ptrdiff_t>(end), 0);
  std::vector<std::pair<std::size_t, std::size_t>> stack = {{begin, end}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    double worst = 0.0;
    std::size_t at = i;
    for (std::size_t k = i + 1; k < j; ++k)
      if (const double d = synchronised_distance(tr, i, j, k); d > worst) {
        worst = d;
        at = k;
      }
    if (worst <= tol_m) continue;
    keep[at] = 1;
    stack.push_back({i, at});
    stack.push_back({at, j});
  }
  Trajectory out;
  std::size_t new_end = 0;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    if (!keep[k]) continue;
    if (k == end) new_end = out.size();
    out.push_back(tr[k]);
  }
  if (out.size() == tr.size()) return false;
  tr = std::move(out);
  e.body_end = new_end;
  return true;
}

// Where rows up to j put the UAV at time t_s (times[k] the time of row k), from row k on: k
// advances to the row before t_s (later times ask on from there).
Vec3 position_at(const Trajectory& tr, const std::vector<double>& times, std::size_t& k, std::size_t j, double t_s) {
  while (k + 1 < j && times[k + 1] < t_s) ++k;
  const double span = times[k + 1] - times[k];
  const double f = span > 0.0 ? std::clamp((t_s - times[k]) / span, 0.0, 1.0) : 0.0;
  return tr[k].p + f * (tr[k + 1].p - tr[k].p);
}

// Rows [i, j] retimed (`times`) at one horizontal speed (ArduCopter's waypoint speed), their ends
// kept; returns the farthest the retimed UAV is from where the plan (`planned`, the rows' times)
// has it at the same moment, and the row where, in `worst`.
double retimed(const Trajectory& tr, const std::vector<double>& planned, std::size_t i, std::size_t j,
               std::vector<double>& times, std::size_t& worst) {
  double total_m = 0.0;
  for (std::size_t k = i; k < j; ++k) total_m += (tr[k + 1].p - tr[k].p).head<2>().norm();
  double along_m = 0.0, farthest_m = 0.0;
  for (std::size_t k = i + 1; k < j; ++k) {
    along_m += (tr[k].p - tr[k - 1].p).head<2>().norm();
    times[k] = tr[i].t_s + (tr[j].t_s - tr[i].t_s) * along_m / total_m;
  }
  worst = i;
  std::size_t on_retimed = i, on_planned = i;  // both clocks increase with k
  for (std::size_t k = i + 1; k < j; ++k) {    // each row against the other clock, both ways
    const double off_m = std::max((position_at(tr, times, on_retimed, j, planned[k]) - tr[k].p).norm(),
                                  (position_at(tr, planned, on_planned, j, times[k]) - tr[k].p).norm());
    if (off_m > farthest_m) farthest_m = off_m, worst = k;
  }
  return farthest_m;
}

// ArduCopter takes up a speed commanded as a leg begins only on a long leg
// (copter_speed_change_leg_m): elsewhere a slow-down is flown late and a speed-up a leg late. So
// its rows are flown in stretches at one speed, each beginning where it can take that speed up
// (a long leg, the body's start, a hold, a vertical leg), retimed at one horizontal speed, within
// tol_m of where the plan has the UAV at every moment (else split at the farthest row, a speed
// change on a short leg kept). The retimed rows are verified with everything else that flies.
// Returns whether a row's time changed.
bool copter_stretches(ExportedUav& e, double tol_m) {
  Trajectory& tr = e.plan.trajectory;
  const std::size_t begin = e.body_begin, end = e.body_end;
  if (end <= begin + 1) return false;
  std::vector<char> cut(tr.size(), 0);
  cut[begin] = cut[end] = 1;
  for (std::size_t k = begin; k < end; ++k) {
    const double h_m = (tr[k + 1].p - tr[k].p).head<2>().norm(), dt = tr[k + 1].t_s - tr[k].t_s;
    const double before_mps =
        k > begin ? (tr[k].p - tr[k - 1].p).head<2>().norm() / std::max(tr[k].t_s - tr[k - 1].t_s, 1e-12) : 0.0;
    if (h_m <= kHoldMove_m || dt <= 0.0) {  // a hold or a vertical leg: flown as planned
      cut[k] = cut[k + 1] = 1;
      continue;
    }
    if (h_m >= copter_speed_change_leg_m(std::max(before_mps, h_m / dt))) cut[k] = 1;
  }
  std::vector<double> planned(tr.size());
  for (std::size_t k = 0; k < tr.size(); ++k) planned[k] = tr[k].t_s;
  std::vector<double> times = planned;
  std::vector<std::pair<std::size_t, std::size_t>> stack;
  for (std::size_t i = begin, j = begin + 1; j <= end; ++j)
    if (cut[j]) {
      stack.push_back({i, j});
      i = j;
    }
  bool changed = false;
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j <= i + 1) continue;
    std::size_t worst = i;
    if (retimed(tr, planned, i, j, times, worst) > tol_m) {
      for (std::size_t k = i + 1; k < j; ++k) times[k] = planned[k];
      stack.push_back({i, worst});
      stack.push_back({worst, j});
      continue;
    }
    for (std::size_t k = i + 1; k < j; ++k) changed |= times[k] != planned[k];
  }
  for (std::size_t k = begin; k <= end; ++k) tr[k].t_s = times[k];
  return changed;
}

// An autopilot rounds its turns by about what it flies in this time (its S-curves at the
// accelerations schedule.json asks for): chords within that distance cut corners it would not
// fly, and spare it turns that cost it time (docs/decisions/0020-flown-timing.md).
constexpr double kAutopilotChord_s = 0.3;
// ArduCopter's stretches at one speed keep within what it flies in this time of where the plan
// has it (copter_stretches): a second of the plan's clock.
constexpr double kCopterStretch_s = 1.0;

double simplify_tolerance_m(const ExportedUav& e, const ExportOptions& opt) {
  if (opt.simplify_m >= 0.0) return opt.simplify_m;
  if (opt.autopilot) return std::max(e.spec->radius_m, kAutopilotChord_s * e.spec->speed.cruise_mps);
  return e.spec->model ? e.spec->radius_m : 0.0;
}

// Each UAV's rows changed by `apply(e, tolerance)` within its `tolerance_m(e)`, every tolerance
// halved until what is changed holds with everything else that flies (down to a centimetre; else
// the rows stay as they are).
template <class Tolerance, class Apply>
void halved_until_flights_hold(const Scenario& sc, std::vector<ExportedUav>& uavs, Tolerance tolerance_m, Apply apply) {
  double widest_m = 0.0;
  for (const ExportedUav& e : uavs) widest_m = std::max(widest_m, tolerance_m(e));
  for (double scale = 1.0; widest_m * scale >= 0.01; scale *= 0.5) {
    std::vector<ExportedUav> changed_uavs = uavs;
    bool changed = false;
    for (ExportedUav& e : changed_uavs)
      if (const double tol = tolerance_m(e) * scale; tol > 0.0) changed |= apply(e, tol);
    if (!changed) return;
    if (verify_flights(sc, changed_uavs).empty()) {
      uavs = std::move(changed_uavs);
      return;
    }
  }
}

// Each UAV flown as chords within its tolerance (else every row is flown).
void fly_chords(const Scenario& sc, std::vector<ExportedUav>& uavs, const ExportOptions& opt) {
  halved_until_flights_hold(
      sc, uavs, [&opt](const ExportedUav& e) { return simplify_tolerance_m(e, opt); }, simplify_body);
}

// ArduCopter missions' rows in stretches at one speed (copter_stretches) within what each UAV flies
// in kCopterStretch_s (else the rows keep the plan's times).
void fly_copter_stretches(const Scenario& sc, std::vector<ExportedUav>& uavs) {
  halved_until_flights_hold(
      sc, uavs,
      [](const ExportedUav& e) { return std::max(e.spec->radius_m, kCopterStretch_s * e.spec->speed.cruise_mps); },
      copter_stretches);
}

}  // namespace

namespace {

// A flat world's flight lifted to opt.flat_altitude_m (ExportOptions), its end brought down.
void lift_flat(ExportedUav& e, const ExportOptions& opt) {
  const double lift = opt.flat_altitude_m;
  for (TrajectorySample& row : e.plan.trajectory) row.p.z() += lift;
  e.takeoff_to.z() += lift;
  for (Vec3& p : e.return_points) p.z() += lift;
  if (e.end == MissionEnd::land && e.touchdown)  // level to above the touch-down (none: straight down), down
    append_landing(e.plan.trajectory, Vec3(e.touchdown->x(), e.touchdown->y(), e.plan.trajectory.back().p.z()),
                   *e.touchdown, e.spec->speed.cruise_mps, arducopter_timing(opt));
  if (e.end == MissionEnd::rtl) append_flight(e.plan.trajectory, {e.home}, e.spec->speed.cruise_mps);
}

bool flat_world(const Scenario& sc) {
  return sc.world.bounds().max.z() - sc.world.bounds().min.z() <= kClearTolerance_m;
}

// Items a UAV's mission takes (a flat world's as lifted: with its climb and its landing).
std::size_t items_needed(const Scenario& sc, const ExportedUav& e, const ExportOptions& opt) {
  if (!flat_world(sc)) return mission_items(sc, e, opt).size();
  ExportedUav lifted = e;
  lift_flat(lifted, opt);
  return mission_items(sc, lifted, opt).size();
}

// Missions over the firmware's store are flown as fewer chords: the tolerance doubles from a
// centimetre until each fits and the chords hold with everything else that flies. Returns
// {ID, why} for each UAV that never fits (its mission would be refused at upload).
std::vector<std::pair<std::string, std::string>> fit_item_limit(const Scenario& sc, std::vector<ExportedUav>& uavs,
                                                                const ExportOptions& opt) {
  if (!opt.autopilot || !sc.origin) return {};
  const auto limit = static_cast<std::size_t>(mission_item_limit(opt));
  const auto over = [&](const ExportedUav& e) { return items_needed(sc, e, opt) > limit; };
  if (std::none_of(uavs.begin(), uavs.end(), over)) return {};
  const double diagonal_m = sc.world.bounds().extent().norm();
  for (double tol_m = 0.01; tol_m < 2.0 * diagonal_m; tol_m *= 2.0) {
    std::vector<ExportedUav> chords = uavs;
    bool fits = true;
    for (ExportedUav& e : chords)
      if (over(e)) {
        simplify_body(e, tol_m);
        fits = fits && !over(e);
      }
    if (fits && verify_flights(sc, chords).empty()) {
      uavs = std::move(chords);
      return {};
    }
  }
  std::vector<std::pair<std::string, std::string>> why;
  for (const ExportedUav& e : uavs)
    if (over(e))
      why.emplace_back(e.spec->id, e.spec->id + ": its mission takes " + std::to_string(items_needed(sc, e, opt)) +
                                       " items, more than the " + std::to_string(limit) + " the " +
                                       (opt.firmware == Firmware::px4 ? "PX4" : "ArduPilot") +
                                       " firmware stores (--max-items), and no chords of its flight that few hold");
  return why;
}

}  // namespace

int mission_item_limit(const ExportOptions& opt) {
  if (opt.max_items > 0) return opt.max_items;
  return opt.firmware == Firmware::px4 ? 500 : 650;
}

Trajectory exported_rows(const ExportedUav& e) {
  const Trajectory& tr = e.plan.trajectory;
  if (!e.takeoff_before || tr.empty()) return tr;
  std::vector<Vec3> up{e.home};
  if ((e.takeoff_to - e.home).norm() > 0.0) up.push_back(e.takeoff_to);
  if ((tr.front().p - up.back()).norm() > 0.0) up.push_back(tr.front().p);
  double len_m = 0.0;
  for (std::size_t k = 1; k < up.size(); ++k) len_m += (up[k] - up[k - 1]).norm();
  Trajectory out{{tr.front().t_s - len_m / e.spec->speed.cruise_mps, up.front()}};
  for (std::size_t k = 1; k + 1 < up.size(); ++k)
    out.push_back({out.back().t_s + (up[k] - up[k - 1]).norm() / e.spec->speed.cruise_mps, up[k]});
  out.insert(out.end(), tr.begin(), tr.end());
  return out;
}

VerifiedExport verified_export(const Scenario& sc, const Plan& plan, const ExportOptions& opt) {
  VerifiedExport out;
  for (const UavPlan& u : plan.uavs)
    if (!sc.find_uav(u.id)) throw ExportError("plan UAV '" + u.id + "' is not in scenario '" + sc.name + "'");
  out.violations = verify_plan(sc, plan);
  auto first_violation = [&](const std::string& id) -> const Violation* {
    for (const Violation& v : out.violations)
      if (v.uav == id) return &v;
    return nullptr;
  };
  const Builder builder(sc, opt);
  for (const UavPlan& up : plan.uavs) {
    if (up.status != Status::solved || up.trajectory.size() < 2) {
      out.left_out.push_back(up.id + ": " + std::string(to_string(up.status)) +
                             (up.message.empty() ? std::string() : " (" + up.message + ")"));
      continue;
    }
    if (const Violation* v = first_violation(up.id)) {
      out.left_out.push_back(up.id + ": does not hold: " + describe(*v));
      continue;
    }
    ExportedUav e;
    std::string note;
    if (const std::string why = builder.build(*sc.find_uav(up.id), up, e, note); !why.empty()) {
      out.left_out.push_back(up.id + ": " + why);
      continue;
    }
    if (!note.empty()) out.notes.push_back(up.id + ": written as planned, without its added legs: " + note);
    out.uavs.push_back(std::move(e));
  }
  for (const Violation& v : out.violations)
    if (v.uav.empty()) out.left_out.push_back("the plan: " + describe(v));
  // Autopilot missions and model-flown trajectories flown as chords that hold with everything
  // else that flies.
  fly_chords(sc, out.uavs, opt);
  if (arducopter_timing(opt)) fly_copter_stretches(sc, out.uavs);
  // The added legs, with everything else that flies: a UAV whose legs do not hold goes.
  std::set<std::string> failed;
  for (auto& [id, why] : fit_item_limit(sc, out.uavs, opt)) {
    failed.insert(id);
    out.left_out.push_back(std::move(why));
  }
  for (Violation& v : verify_flights(sc, out.uavs)) {
    if (failed.insert(v.uav).second)
      out.left_out.push_back(v.uav + ": with its " + std::string(to_string(opt.end)) + " legs: " + describe(v));
    out.violations.push_back(std::move(v));
  }
  for (const ExportedUav& e : out.uavs)
    if (!failed.count(e.spec->id))
      if (const std::string why = circle_meets(sc, e, out.uavs); !why.empty()) {
        failed.insert(e.spec->id);
        out.left_out.push_back(e.spec->id + ": " + why);
      }
  std::erase_if(out.uavs, [&](const ExportedUav& e) { return failed.count(e.spec->id) > 0; });
  if (flat_world(sc))
    for (ExportedUav& e : out.uavs) lift_flat(e, opt);
  return out;
}

}  // namespace uavplan
