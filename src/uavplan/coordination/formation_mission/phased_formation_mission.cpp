#include "uavplan/coordination/formation_mission/phased_formation_mission.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <stdexcept>

#include "uavplan/coordination/contract/runway.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation_mission/formation_group.h"
#include "uavplan/coordination/formation_mission/landing.h"
#include "uavplan/coordination/timing.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/registry.h"
#include "uavplan/simulation/vehicle_flight.h"

namespace uavplan {
namespace {

constexpr double kG_mps2 = 9.81;
// A route waypoint this near a task point is that task point (pso_mpc puts one on each).
constexpr double kTaskPointMatch_m = 1.0;
// P5's aircraft (P5-notes 3): 150 m/s turning at 2.2 deg/s. Its lengths and rates are scaled to
// other aircraft from these.
constexpr double kP5Cruise_mps = 150.0, kP5TurnRate_deg_s = 2.2;

// The model a UAV flies through: its own, or papers.md P5's defaults (time constants; the turn rate of
// a 30 deg bank at cruise; climb at most 20 m/s (P5's gradient for slower aircraft) and within
// its climb angle at its least speed;
// the horizontal speed at most what leaves the maximum speed in 3-D while climbing; the vertical
// acceleration at most max_vertical_accel_mps2).
AutopilotModel mission_model(const UavSpec& u, const FormationMissionOptions& o) {
  const AutopilotModel own = autopilot_of(u);
  AutopilotLimits lim = own.limits();
  if (!u.max_turn_rate_rad_s) lim.max_turn_rate_rad_s = kG_mps2 * std::tan(deg_to_rad(o.bank_deg)) / u.speed.cruise_mps;
  // Without its own: P5's 20 m/s at its 150 m/s, the same climb gradient for slower aircraft.
  double climb =
      u.max_climb_rate_mps.value_or(o.max_climb_rate_mps * std::min(1.0, u.speed.cruise_mps / kP5Cruise_mps));
  if (u.max_climb_rad < kPi / 2 - kUnlimitedAngleSlack_rad)
    climb = std::min(climb, 0.95 * std::max(u.speed.min_mps, 1.0) * std::tan(u.max_climb_rad));
  lim.max_climb_rate_mps = climb;
  // An altitude order that jumps (a layer left for the shape's heights) must not flip the climb
  // within a row: a turn over the limit in the vertical.
  lim.max_vertical_accel_mps2 = o.max_vertical_accel_mps2;
  // The model holds the horizontal speed; climbing at full rate it must stay within the maximum.
  lim.speed.max_mps = std::sqrt(std::max(0.0, u.speed.max_mps * u.speed.max_mps - climb * climb)) * (1.0 - 1e-6);
  lim.speed.cruise_mps = std::min(lim.speed.cruise_mps, lim.speed.max_mps);
  return AutopilotModel(own.params(), lim);
}

double lift_off_mps(const UavSpec& u) { return std::max(u.speed.min_mps, 0.5 * u.speed.cruise_mps); }

struct GroundRun {
  Trajectory ground;  // parked, taxi to the threshold, take-off roll
  double lift_s = 0.0;
  AutopilotState lift_off;
};

// Take-off in turn, the nearest to the threshold first.
std::vector<std::size_t> takeoff_order(const Scenario& sc, const std::vector<Vec3>& starts) {
  const Vec3& thr = sc.mission.airfield->position;
  std::vector<std::size_t> order(sc.uavs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return (starts[a] - thr).norm() < (starts[b] - thr).norm(); });
  return order;
}

// The altitude layers of the form-up, the first to take off highest.
std::vector<double> layers(const std::vector<std::size_t>& order, const FormationMissionOptions& o) {
  const std::size_t n = order.size();
  std::vector<double> layer(n);
  for (std::size_t k = 0; k < n; ++k)
    layer[order[k]] = o.layer_spacing_m * (static_cast<double>(n - 1 - k) - 0.5 * (n - 1));
  return layer;
}

// Parked until it taxis to the threshold, then the roll from rest to lift-off at `lift_s`.
GroundRun ground_run(const Airfield& af, const Vec3& start, double lift_s, double v_lo, double acc,
                     const FormationMissionOptions& o) {
  const Vec3 dir(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0);
  const double roll_s = v_lo / acc, roll_m = 0.5 * v_lo * roll_s;
  const double roll_start = lift_s - roll_s, taxi_start = roll_start - (start - af.position).norm() / o.taxi_mps;
  GroundRun d;
  d.ground.push_back({0.0, start});
  if (taxi_start > 0.0) d.ground.push_back({taxi_start, start});
  append_straight_run(d.ground, af.position, o.taxi_mps, o.taxi_mps, 1.0);
  if (d.ground.back().t_s < roll_start) d.ground.push_back({roll_start, af.position});
  const Vec3 lift_at = af.position + roll_m * dir;
  append_straight_run(d.ground, lift_at, 0.0, v_lo, 1.0);
  d.lift_s = lift_s;
  d.lift_off.position = lift_at;
  d.lift_off.speed_mps = v_lo;
  d.lift_off.heading_rad = af.runway_heading_rad;
  return d;
}

// How long after lift-off a UAV climbing out on `climb` is still on the runway (contract/runway.h).
double on_runway_after_lift_s(const Airfield& af, const AutopilotModel& m, AutopilotState s,
                              const AutopilotCommand& climb, double dt_s) {
  constexpr double kLongestClimbOut_s = 600.0;
  double t = 0.0;
  for (; on_runway(af, s.position) && t < kLongestClimbOut_s; t += dt_s) m.advance(s, climb, dt_s);
  return t;
}

// Take-off in turn (`order`): each lines up once the one before has climbed off the runway
// (contract: one UAV on it at a time; `margin_s` for the rows recorded after the exit), and lifts
// off at least takeoff_interval_s after it. climb_to_m: each UAV's altitude while it climbs out.
std::vector<GroundRun> departures(const Scenario& sc, const std::vector<Vec3>& starts,
                                  const std::vector<std::size_t>& order, const std::vector<AutopilotModel>& models,
                                  const std::vector<double>& climb_to_m, const FormationMissionOptions& o, double dt_s,
                                  double margin_s) {
  const Airfield& af = *sc.mission.airfield;
  std::vector<GroundRun> out(sc.uavs.size());
  double prev_lift = -1e300, runway_free = 0.0;
  for (const std::size_t i : order) {
    const UavSpec& u = sc.uavs[i];
    const double v_lo = lift_off_mps(u);
    const double acc =
        std::max(o.min_roll_accel_mps2, v_lo * v_lo / (2.0 * o.lift_off_within_runway * af.runway_length_m));
    const double ground_s = (starts[i] - af.position).norm() / o.taxi_mps + v_lo / acc;
    const auto on_step = [&](double t) { return std::ceil(t / dt_s - kWholeNumberSlack) * dt_s; };
    double lift = on_step(std::max(prev_lift + o.takeoff_interval_s, ground_s));
    GroundRun d = ground_run(af, starts[i], lift, v_lo, acc, o);
    const std::vector<TimeSpan> occ = runway_occupancy(af, d.ground);
    if (!occ.empty() && occ.front().from_s < runway_free) {  // lines up later, all of it shifted
      lift = on_step(lift + runway_free - occ.front().from_s);
      d = ground_run(af, starts[i], lift, v_lo, acc, o);
    }
    const AutopilotCommand climb{v_lo, climb_to_m[i], af.runway_heading_rad};
    runway_free = lift + on_runway_after_lift_s(af, models[i], d.lift_off, climb, dt_s) + margin_s;
    prev_lift = lift;
    out[i] = std::move(d);
  }
  return out;
}

std::vector<double> climb_altitudes(double z_form, const std::vector<double>& layer) {
  std::vector<double> z;
  z.reserve(layer.size());
  for (const double l : layer) z.push_back(z_form + l);
  return z;
}

// The formation as one body: its slots' mean, its half-width, the widest UAV, the slowest
// cruise and the slowest turn rate (of its UAVs, and of its shape enlarged `enlargement` times).
struct FormationBody {
  Vec3 mean_slot = Vec3::Zero();
  double half_width_m = 0.0, widest_m = 0.0, cruise_mps = World::kInf, turn_rate_rad_s = World::kInf;
};

FormationBody formation_body(const Scenario& sc, const std::vector<AutopilotModel>& models, double enlargement) {
  const std::size_t n = sc.uavs.size();
  FormationBody b;
  for (const Vec3& s : formation_shape(sc)) b.mean_slot += s / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    b.half_width_m = std::max(b.half_width_m, (formation_shape(sc)[i] - b.mean_slot).head<2>().norm());
    b.widest_m = std::max(b.widest_m, sc.uavs[i].radius_m);
    b.cruise_mps = std::min(b.cruise_mps, sc.uavs[i].speed.cruise_mps);
    b.turn_rate_rad_s = std::min(b.turn_rate_rad_s, models[i].limits().max_turn_rate_rad_s);
  }
  // Turning as a body at rate w, a UAV r from the shape's centre flies r w faster or slower than
  // it: with the shape enlarged (form-up, dismiss), within its speeds (where they leave room).
  for (std::size_t i = 0; i < n; ++i) {
    const double r_m = enlargement * (formation_shape(sc)[i] - b.mean_slot).head<2>().norm();
    const SpeedLimits& v = sc.uavs[i].speed;
    const double room_mps = std::min(v.max_mps - b.cruise_mps, b.cruise_mps - v.min_mps);
    if (r_m > 0.0 && room_mps > 0.0) b.turn_rate_rad_s = std::min(b.turn_rate_rad_s, room_mps / r_m);
  }
  return b;
}

// P5's lengths (the departure point 15 km past the runway, the dismiss trigger 30 km out,
// waypoints passed within 300 m, the landing cylinder of 3 km 10 km out, the gate at 300 m 6 km
// out: P5-notes 3-5) are its aircraft's: 150 m/s turning at 2.2 deg/s, a radius of 3.9 km. Other
// aircraft get them in proportion to their turn radius (the formation's: its slowest cruise at
// its slowest turn rate), as P5's scene drawn at their scale. The form-up's layers are twice the
// separation apart (P5: 100 m for 50 m), the lowest layer's reference 50 s of the slowest climb
// above the airfield (P5: 1000 m at 20 m/s) and above the layers. Values in planner.params stay.
void scale_to_formation(FormationMissionOptions& o, const Params& given, const FormationBody& b, double separation_m,
                        double climb_mps, std::size_t n) {
  const double p5_radius_m = kP5Cruise_mps / deg_to_rad(kP5TurnRate_deg_s);
  double s = b.cruise_mps / b.turn_rate_rad_s / p5_radius_m;
  if (!std::isfinite(s) || std::abs(s - 1.0) < 1e-9) s = 1.0;
  o.departure_after_runway_m *= s;
  o.steering_switch_m *= s;
  if (!given.count("dismiss_within_m")) o.dismiss_within_m *= s;
  o.landing.cylinder_radius_m *= s;
  o.landing.cylinder_before_threshold_m *= s;
  o.landing.gate_before_threshold_m *= s;
  o.landing.gate_height_m *= s;
  // The spiral's descent (P5: at most 10 m/s at 150 m/s) at the same gradient for slower aircraft.
  o.landing.max_descent_mps *= std::min(1.0, b.cruise_mps / kP5Cruise_mps);
  constexpr double kLayersPerSeparation = 2.0, kFormUpClimb_s = 50.0;
  if (!given.count("layer_spacing_m")) o.layer_spacing_m = kLayersPerSeparation * separation_m;
  if (!given.count("form_up_height_m"))
    o.form_up_height_m = std::max(kFormUpClimb_s * climb_mps, o.layer_spacing_m * static_cast<double>(n));
}

Vec3 runway_direction(const Airfield& af) {
  return {std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0};
}

// The airfield's geometry (scale_to_formation) fitted to the world: where the cylinder would
// leave the bounds, it and the gate come in toward the threshold in proportion (radius,
// distances and the gate's height: the glide keeps its slope), as far as every UAV can still
// circle inside it at its least speed (where one cannot, they grow as far as it needs); the
// departure point comes in likewise. Empty when it
// fits, else why not.
std::string fit_airfield(const Scenario& sc, const std::vector<AutopilotModel>& models, const FormationBody& b,
                         FormationMissionOptions& o) {
  const Airfield& af = *sc.mission.airfield;
  const Aabb& box = sc.world.bounds();
  const Vec3 dir = runway_direction(af);
  LandingOptions& l = o.landing;
  // The cylinder's disc, kept the widest body inside the bounds: scale k of (before, radius).
  double k = World::kInf;
  for (int a = 0; a < 2; ++a) {
    const double thr = af.position[a], back = l.cylinder_before_threshold_m * dir[a], r = l.cylinder_radius_m;
    if (back + r > 0.0) k = std::min(k, (thr - b.widest_m - box.min[a]) / (back + r));
    if (r - back > 0.0) k = std::min(k, (box.max[a] - b.widest_m - thr) / (r - back));
  }
  double least_k = 0.0;  // every UAV circles inside it (plan_landing: a turn within 0.8 of the radius)
  for (const AutopilotModel& m : models) {
    const double omega =
        std::isfinite(m.limits().max_turn_rate_rad_s) ? m.limits().max_turn_rate_rad_s : deg_to_rad(3.0);
    least_k = std::max(least_k, m.limits().speed.min_mps / omega / (0.8 * l.cylinder_radius_m));
  }
  if (k < least_k)
    return "no room for the landing approach: the landing cylinder (radius " +
           std::to_string(static_cast<long>(least_k * l.cylinder_radius_m)) + " m at least, " +
           std::to_string(static_cast<long>(least_k * l.cylinder_before_threshold_m)) +
           " m before the threshold on the extended centreline) leaves the world's bounds; move the airfield "
           "further from the edge behind its threshold, or turn its runway";
  // Grown only as far as the slowest circle needs, with room to circle on 1.25 turn radii
  // (plan_landing's circle) where the bounds allow.
  k = std::min(k, std::max(1.0, 1.25 * least_k));
  l.cylinder_before_threshold_m *= k;
  l.cylinder_radius_m *= k;
  l.gate_before_threshold_m *= k;
  l.gate_height_m *= k;
  // The departure point: on the runway's line, inside the bounds by the formation's width.
  const double margin = o.enlargement * b.half_width_m + b.widest_m;
  const Vec3 end = af.position + af.runway_length_m * dir;
  for (int a = 0; a < 2; ++a) {
    if (dir[a] > 1e-12)
      o.departure_after_runway_m = std::min(o.departure_after_runway_m, (box.max[a] - margin - end[a]) / dir[a]);
    if (dir[a] < -1e-12)
      o.departure_after_runway_m = std::min(o.departure_after_runway_m, (box.min[a] + margin - end[a]) / dir[a]);
  }
  if (o.departure_after_runway_m < 0.0)
    return "no room to depart: the runway's end lies within the formation's width (" +
           std::to_string(static_cast<long>(margin)) + " m) of the world's bounds ahead of it";
  return {};
}

// The coarse route's problem (pso_mpc): from the departure point after the runway through the
// task points at their entry headings back to the landing cylinder, for a body as wide as the
// enlarged shape plus the turn's overshoot.
Problem coarse_problem(const Scenario& sc, const MissionContext& ctx, const FormationMissionOptions& o,
                       const FormationBody& b, double z_form) {
  const Airfield& af = *sc.mission.airfield;
  const Vec3 dir = runway_direction(af);
  const UavSpec& lead = sc.uavs.front();
  Problem pb;
  pb.uav = lead;
  pb.uav.id = "formation";
  pb.uav.radius_m = o.enlargement * b.half_width_m + b.widest_m +
                    b.cruise_mps / b.turn_rate_rad_s * (1.0 - std::cos(deg_to_rad(o.overshoot_turn_deg)));
  pb.uav.start = af.position + (af.runway_length_m + o.departure_after_runway_m) * dir;
  pb.uav.start.z() = z_form;
  pb.uav.heading_rad = af.runway_heading_rad;
  pb.uav.speed.cruise_mps = b.cruise_mps;
  pb.uav.max_turn_rate_rad_s = o.turn_margin * b.turn_rate_rad_s;  // margin for the shape turning as a body
  pb.uav.model = lead.model.value_or(AutopilotParams{});
  for (const TaskPoint& tp : phased_section(sc).task_points) {
    pb.via.push_back(tp.position);
    pb.via_entry_heading_rad.push_back(tp.entry_heading_rad);
  }
  // Back to the landing cylinder (phase 5) at the last task point's altitude.
  const Vec3 cylinder = af.position - o.landing.cylinder_before_threshold_m * dir;
  pb.goal = Vec3(cylinder.x(), cylinder.y(), phased_section(sc).task_points.back().position.z());
  pb.seed = ctx.options.seed;
  return pb;
}

// The route's waypoints that are task points are flown over; `last_task` the last of them.
std::vector<char> task_fly_over(const Scenario& sc, const std::vector<Vec3>& wps, std::size_t& last_task) {
  std::vector<char> fly_over(wps.size(), 0);
  last_task = 0;
  for (const TaskPoint& tp : phased_section(sc).task_points)
    for (std::size_t k = last_task + 1; k < wps.size(); ++k)
      if ((wps[k] - tp.position).norm() < kTaskPointMatch_m) {
        fly_over[k] = 1, last_task = k;
        break;
      }
  return fly_over;
}

// The flight of one formation_mission, phase by phase, on one FormationGroup; each phase a
// method that returns whether it completed.
class PhasedFlight {
 public:
  PhasedFlight(const Scenario& sc, const MissionContext& ctx, const FormationMissionOptions& o,
               const std::vector<Vec3>& starts, const std::vector<AutopilotModel>& models, const FormationBody& body,
               const std::vector<Vec3>& wps, double route_m, double z_form)
      : sc_(sc),
        ctx_(ctx),
        o_(o),
        n_(sc.uavs.size()),
        af_(*sc.mission.airfield),
        body_(body),
        z_form_(z_form),
        fly_over_(task_fly_over(sc, wps, last_task_)),
        steer_(wps, fly_over_, body.cruise_mps / body.turn_rate_rad_s, o.steering_switch_m),
        order_(takeoff_order(sc, starts)),
        layer_(layers(order_, o)),
        dep_(departures(sc, starts, order_, models, climb_altitudes(z_form, layer_), o, go_.dt_s,
                        go_.record_s + go_.dt_s)),
        group_(models, formation_shape(sc),
               phased_section(sc).topology.empty() ? complete_topology(n_) : phased_section(sc).topology, go_, 0.0),
        route_s_(3.0 * route_m / body.cruise_mps + o.step_timeout_s),
        models_(models) {
    up_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) up_[i] = formation_shape(sc)[i].z() - body.mean_slot.z();
    order_now_.speed_mps = body.cruise_mps;
    order_now_.heading_rad = af_.runway_heading_rad;
    order_now_.scale = o.enlargement;
    order_now_.altitude_m.assign(n_, z_form);
    offsets_ = layer_;
  }

  // Phases 1-5; false with failure() set where one does not complete.
  bool fly() {
    // A phase that fails ends the flight; the later ones are logged as ending then.
    bool ok = phase("form_up", form_up());
    ok = phase("mission", ok && task_points());
    ok = phase("return", ok && back());
    ok = phase("dismiss", ok && dismiss());
    return ok && land();
  }
  const std::string& failure() const { return failed_; }
  const FormationLog& log() const { return log_; }
  // UAV i's rows: on the ground, in the group, landing.
  Trajectory trajectory(std::size_t i) const {
    Trajectory tr = dep_[i].ground;
    for (const TrajectorySample& s : group_.trajectory(i))
      if (s.t_s > tr.back().t_s + kSameTime_s) tr.push_back(s);
    for (const TrajectorySample& s : landings_[i])
      if (s.t_s > tr.back().t_s + kSameTime_s) tr.push_back(s);
    return tr;
  }

 private:
  // Phase 1: take-off in turn, layers, the enlarged shape, heights, shrink.
  bool form_up() {
    if (!run_until([&] { return all_joined() && in_shape(); }, o_.step_timeout_s)) return false;
    offsets_ = up_;
    return run_until([&] { return in_shape(); }, o_.step_timeout_s) && scale_to(1.0);
  }
  // Phase 2: the route through the task points.
  bool task_points() {
    return run_until([&] { return steer_.next() > last_task_; }, route_s_);
  }
  // Phase 3: back towards the airfield until within dismiss_within_m.
  bool back() {
    return run_until(
        [&] { return !route_left_ || (group_.centroid() - af_.position).head<2>().norm() < o_.dismiss_within_m; },
        route_s_);
  }
  // Phase 4, on the way to the landing cylinder: the reverse of form-up.
  bool dismiss() {
    if (!scale_to(o_.enlargement)) return false;
    offsets_ = layer_;
    return run_until([&] { return in_shape(); }, o_.step_timeout_s);
  }
  bool land();
  void step();
  bool run_until(const std::function<bool()>& done, double limit_s);
  bool scale_to(double target);
  bool all_joined() const {
    for (std::size_t i = 0; i < n_; ++i)
      if (!group_.in_formation(i)) return false;
    return true;
  }
  bool in_shape() const { return group_.shape_error_m(order_now_) < o_.shape_tolerance_m; }
  bool phase(const char* name, bool ok);

  const Scenario& sc_;
  const MissionContext& ctx_;
  const FormationMissionOptions& o_;
  std::size_t n_;
  const Airfield& af_;
  FormationBody body_;
  double z_form_;
  FormationGroupOptions go_;
  std::size_t last_task_ = 0;
  std::vector<char> fly_over_;
  RouteSteering steer_;
  std::vector<std::size_t> order_;  // of take-off
  std::vector<double> layer_;
  std::vector<GroundRun> dep_;
  FormationGroup group_;
  double route_s_;  // a route phase not ended within this much flight fails the mission
  std::vector<AutopilotModel> models_;
  std::vector<double> up_, offsets_;
  FormationOrder order_now_;
  bool route_left_ = true;
  FormationLog log_;
  std::string failed_;
  std::vector<Trajectory> landings_ = std::vector<Trajectory>(n_);
};

bool PhasedFlight::phase(const char* name, bool ok) {
  if (!ok && failed_.empty()) {
    const std::string buf =
        strf("the %s phase did not complete (at t = %.0f s the shape was %.1f m off, tolerance %.1f m)", name,
             group_.time_s(), group_.shape_error_m(order_now_), o_.shape_tolerance_m);
    failed_ = buf;
  }
  log_.phases.push_back({name, group_.time_s()});
  return ok;
}

// One control sample: lift-offs and joins, then the group under the order, its frame steered
// along the route.
void PhasedFlight::step() {
  const auto solo = [&](std::size_t i) {
    return AutopilotCommand{lift_off_mps(sc_.uavs[i]), z_form_ + layer_[i], af_.runway_heading_rad};
  };
  for (std::size_t i = 0; i < n_; ++i) {
    if (!group_.flying(i) && dep_[i].lift_s <= group_.time_s() + kSameTime_s)
      group_.launch(i, dep_[i].lift_off, FormationGroup::Launch::solo);
    // Straight ahead off the runway, into the consensus once clear of the ground.
    if (group_.flying(i) && group_.state(i).position.z() > af_.position.z() + o_.join_above_m) group_.join(i);
  }
  if (!group_.anyone_in_formation()) return group_.step(order_now_, solo);
  const Vec3 c = group_.centroid();
  route_left_ = steer_.update(c);
  // The frame turns towards phi* no faster than the UAVs can (a waypoint passed behind the
  // centroid must not flip the shape through itself).
  const double most = o_.turn_margin * body_.turn_rate_rad_s * go_.dt_s;
  order_now_.heading_rad +=
      std::clamp(std::remainder(steer_.heading_rad(c) - order_now_.heading_rad, 2.0 * kPi), -most, most);
  for (std::size_t i = 0; i < n_; ++i) order_now_.altitude_m[i] = steer_.altitude_m(c) + offsets_[i];
  group_.step(order_now_, solo);
}

// Steps until `done`; false when `limit_s` of flight pass first (or the stop comes).
bool PhasedFlight::run_until(const std::function<bool()>& done, double limit_s) {
  const double t0 = group_.time_s();
  while (!done()) {
    if (group_.time_s() - t0 > limit_s || ctx_.options.stop.should_stop()) return false;
    step();
  }
  return true;
}

// The shape's scale changes at scale_rate_per_s to `target`, then the shape settles.
bool PhasedFlight::scale_to(double target) {
  return run_until(
      [&] {
        const double dscale = o_.scale_rate_per_s * go_.dt_s;
        order_now_.scale = order_now_.scale < target ? std::min(target, order_now_.scale + dscale)
                                                     : std::max(target, order_now_.scale - dscale);
        return order_now_.scale == target && in_shape();
      },
      o_.step_timeout_s);
}

// Phase 5: in turn, the nearest to the landing cylinder first (eq. 2 for each), each clear of
// those landed before it by the airfield's rule.
bool PhasedFlight::land() {
  const double t_d = group_.time_s();
  for (std::size_t i = 0; i < n_; ++i) group_.release(i);
  std::vector<std::size_t> land(n_);
  std::iota(land.begin(), land.end(), 0);
  const Vec3 centre = af_.position - o_.landing.cylinder_before_threshold_m * runway_direction(af_);
  std::stable_sort(land.begin(), land.end(), [&](std::size_t a, std::size_t b) {
    return (group_.state(a).position - centre).head<2>().norm() < (group_.state(b).position - centre).head<2>().norm();
  });
  std::vector<std::size_t> landed;
  std::vector<std::vector<TimeSpan>> on_runway(n_);  // of those landed, once each
  for (const std::size_t i : land) {
    const auto conflicts = [&](const Trajectory& f) {
      const std::vector<TimeSpan> runway = runway_occupancy(af_, f);
      for (const std::size_t j : landed)
        if (airfield_encounter(sc_, sc_.uavs[i], f, sc_.uavs[j], landings_[j], t_d).conflict ||
            runway_overlap(runway, on_runway[j]))
          return true;
      return false;
    };
    LandingResult r = plan_landing(af_, models_[i], group_.state(i), t_d, o_.landing, conflicts);
    if (!r.solved()) {
      failed_ = sc_.uavs[i].id + "'s landing: " + r.message;
      return false;
    }
    landings_[i] = std::move(r.flight);
    on_runway[i] = runway_occupancy(af_, landings_[i]);
    landed.push_back(i);
  }
  double end = t_d;
  for (const Trajectory& f : landings_)
    if (!f.empty()) end = std::max(end, f.back().t_s);
  log_.phases.push_back({"landing", end});
  log_.eta_s = end;
  return true;
}

// In the air the separation, on the ground their bodies, the runway one at a time (the
// contract's rules): a pair that breaks one fails both.
void check_airfield_rules(const Scenario& sc, Plan& plan) {
  const std::size_t n = sc.uavs.size();
  const Airfield& af = *sc.mission.airfield;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const Trajectory &ti = plan.uavs[i].trajectory, &tj = plan.uavs[j].trajectory;
      const AirfieldEncounter e = airfield_encounter(sc, sc.uavs[i], ti, sc.uavs[j], tj);
      const auto runway = runway_overlap(runway_occupancy(af, ti), runway_occupancy(af, tj));
      if (!e.conflict && !runway) continue;
      const std::string buf = e.conflict ? strf("%.1f m from %s at t = %.1f s, below %.1f m", e.distance_m,
                                                sc.uavs[j].id.c_str(), e.t_s, e.need_m)
                                         : strf("on the runway with %s from t = %.1f to %.1f s", sc.uavs[j].id.c_str(),
                                                runway->from_s, runway->to_s);
      for (const std::size_t k : {i, j}) {
        plan.uavs[k].status = Status::failed;
        plan.uavs[k].reason = Reason::conflict;
        if (plan.uavs[k].message.empty())
          plan.uavs[k].message = k == i ? buf : (e.conflict ? "too close to " : "on the runway with ") + sc.uavs[i].id;
      }
    }
}

}  // namespace

FormationMissionOptions FormationMissionOptions::from_params(const Params& params) {
  ParamReader r(params, "formation_mission");
  FormationMissionOptions o = read(r);
  r.finish();
  return o;
}

FormationMissionOptions FormationMissionOptions::read(ParamReader& r) {
  FormationMissionOptions o;
  o.layer_spacing_m = r.number("layer_spacing_m", o.layer_spacing_m, 0.0, 1e5,
                               "the height between two UAVs' layers while forming up, m");
  o.enlargement =
      r.number("enlargement", o.enlargement, 1.0, 100.0, "the shape's enlargement while forming up and dismissing");
  o.shape_tolerance_m = r.number("shape_tolerance_m", o.shape_tolerance_m, 1e-3, 1e5,
                                 "a form-up or dismiss step ends under this shape error, m");
  o.form_up_height_m =
      r.number("form_up_height_m", o.form_up_height_m, 0.0, 1e5, "the lowest layer's height above the airfield, m");
  o.takeoff_interval_s =
      r.number("takeoff_interval_s", o.takeoff_interval_s, 0.0, 3600.0, "the least time between two lift-offs, s");
  o.dismiss_within_m = r.number("dismiss_within_m", o.dismiss_within_m, 0.0, 1e7,
                                "the formation dismisses within this distance of the airfield, m");
  return o;
}

void PhasedFormationMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  FormationMissionOptions o = FormationMissionOptions::from_params(ctx.mission_params);
  const std::size_t n = sc.uavs.size();
  if (!sc.mission.airfield || formation_shape(sc).size() != n || phased_section(sc).task_points.empty())
    throw std::invalid_argument("a formation_mission needs an airfield, a slot per UAV and a task point");
  const Airfield& af = *sc.mission.airfield;
  std::vector<Vec3> starts;
  std::vector<AutopilotModel> models;
  for (std::size_t i = 0; i < n; ++i) {
    starts.push_back(ctx.ground.start.size() > i && ctx.ground.start[i] ? *ctx.ground.start[i] : sc.uavs[i].start);
    models.push_back(mission_model(sc.uavs[i], o));
  }
  const FormationBody body = formation_body(sc, models, o.enlargement);
  double climb_mps = World::kInf;
  for (const AutopilotModel& m : models) climb_mps = std::min(climb_mps, m.limits().max_climb_rate_mps);
  scale_to_formation(o, ctx.mission_params, body, sc.mission.separation_m, climb_mps, n);
  if (const std::string why = fit_airfield(sc, models, body, o); !why.empty()) {
    fail_all(sc, why, plan);
    return;
  }
  const double z_form = af.position.z() + o.form_up_height_m;
  const UavSpec& lead = sc.uavs.front();
  const double ceiling =
      lead.ceiling_m ? std::min(*lead.ceiling_m, sc.world.bounds().max.z()) : sc.world.bounds().max.z();
  if (z_form + o.layer_spacing_m * n > ceiling) {
    fail_all(sc, "no room for the form-up's altitude layers below the ceiling", plan);
    return;
  }
  PlanResult route;  // pso_mpc keeps the body (and its turns) inside the bounds too
  try {
    route = make_planner(ctx.algorithm, ctx.params)
                ->plan(coarse_problem(sc, ctx, o, body, z_form), sc.world, ctx.options.stop);
  } catch (const std::invalid_argument& e) {
    route.message = e.what();
  }
  if (route.status != Status::solved) {
    fail_all(sc, "the formation's route: " + route.message, plan);
    return;
  }
  const std::vector<Vec3>& wps = route.route.waypoints;
  PhasedFlight flight(sc, ctx, o, starts, models, body, wps, route.route.length_m(), z_form);
  const bool ok = flight.fly();
  for (std::size_t i = 0; i < n; ++i) {
    Trajectory tr = flight.trajectory(i);
    std::vector<Vec3> w{starts[i]};
    w.insert(w.end(), wps.begin(), wps.end());
    w.push_back(tr.back().p);
    plan.uavs.push_back(
        flown_plan(sc.uavs[i].id, ok, ok ? "" : flight.failure(), std::move(w), ok ? std::move(tr) : Trajectory{}));
  }
  if (ok) check_airfield_rules(sc, plan);
  plan.formation = flight.log();
}

}  // namespace uavplan
