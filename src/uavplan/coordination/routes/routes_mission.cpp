#include "uavplan/coordination/routes/routes_mission.h"

#include <Eigen/Geometry>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "uavplan/coordination/routes/local_layer.h"
#include "uavplan/coordination/routes/rolling_window.h"
#include "uavplan/coordination/routes/route_problem.h"
#include "uavplan/coordination/routes/space_time_routes.h"
#include "uavplan/coordination/spacetime/space_time_table.h"
#include "uavplan/coordination/spacetime/uav_lattice.h"
#include "uavplan/coordination/timing.h"
#include "uavplan/core/text.h"
#include "uavplan/planning/registry.h"
#include "uavplan/simulation/vehicle_flight.h"

namespace uavplan {
namespace {

bool senses(const UavSpec& u) { return u.sensor_range_m.has_value(); }

// How the UAVs without sensors are kept apart: departure delays, space and time together, or
// (auto) delays and, where they leave a UAV in conflict, space and time when that solves more.
enum class Deconfliction { automatic, delays, space_time };

struct RoutesOptions {
  LocalLayer local;
  Deconfliction deconfliction = Deconfliction::automatic;
  SpaceTimeRoutesOptions space_time;
};

RoutesOptions routes_options(const MissionContext& ctx) {
  ParamReader r(ctx.mission_params, ctx.algorithm);
  RoutesOptions o;
  o.local = local_layer(ctx, r);
  const std::string d =
      r.choice("deconfliction", "auto", {"auto", "delays", "space_time"},
               "departure delays, space and time, or auto: delays, then space and time where that solves more");
  if (d == "delays") o.deconfliction = Deconfliction::delays;
  if (d == "space_time") o.deconfliction = Deconfliction::space_time;
  const std::string m = r.choice("space_time_method", "auto", {"auto", "prioritized", "ecbs", "cbs"},
                                 "the space-time solver (auto: prioritised planning, then ECBS)");
  parse_mapf_method(m, o.space_time.method);
  o.space_time.cell_m = r.number("space_time_cell_m", 0.0, 0.0, 1e6,
                                 "the space-time lattice's spacing, m; 0: a little above the separation");
  r.finish();
  return o;
}

// The UAVs space and time may plan: those without sensors that have a goal, flown as point masses
// (a UAV with an autopilot model flies its own route, timed by delays).
std::vector<std::size_t> timed_uavs(const Scenario& sc) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i)
    if (!senses(sc.uavs[i]) && !sc.uavs[i].model && sc.uavs[i].goal) out.push_back(i);
  return out;
}

std::size_t solved_among(const Plan& plan, const std::vector<std::size_t>& which) {
  return static_cast<std::size_t>(
      std::count_if(which.begin(), which.end(), [&](std::size_t i) { return plan.uavs[i].status == Status::solved; }));
}

// The UAVs' routes, planned ahead of their timing on the run's threads (each route is its own
// problem with its own seed, so the routes are those planned one by one) and taken in order: a
// stop leaves the UAVs timed so far complete, as one by one. A worker has its share of the
// threads and of the memory cap; a route that fails within its share is planned again with the
// whole cap while the workers wait, so a grid that fits the run only alone still gets its chance
// and the cap holds. One thread: each route is planned when it is taken.
class RoutesAhead {
 public:
  RoutesAhead(const Scenario& sc, const Planner& planner, const MissionOptions& opt, const GroundPoints& ground)
      : sc_(sc),
        planner_(planner),
        opt_(opt),
        ground_(ground),
        n_(sc.uavs.size()),
        routes_(n_),
        errors_(n_),
        done_(n_, 0) {
    const int workers = std::max(1, std::min(opt.stop.threads(), static_cast<int>(n_)));
    if (workers == 1) return;
    share_ = opt.stop.with_threads(std::max(1, opt.stop.threads() / workers))
                 .with_memory_cap(opt.stop.memory_cap_bytes() / static_cast<std::uint64_t>(workers));
    for (int w = 0; w < workers; ++w) pool_.emplace_back([this] { work(); });
  }
  ~RoutesAhead() {
    {
      const std::lock_guard<std::mutex> lock(m_);
      quit_ = true;
      held_ = false;
    }
    cv_.notify_all();
    for (std::thread& t : pool_) t.join();
  }
  RoutesAhead(const RoutesAhead&) = delete;
  RoutesAhead& operator=(const RoutesAhead&) = delete;

  // UAV i's route; none where the stop came before it was planned.
  std::optional<PlanResult> take(std::size_t i) {
    if (pool_.empty()) return opt_.stop.should_stop() ? std::nullopt : std::optional(plan(i, opt_.stop));
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return done_[i] != 0; });
    if (errors_[i]) std::rethrow_exception(errors_[i]);
    std::optional<PlanResult> r = std::move(routes_[i]);
    const bool retry = r && r->status != Status::solved && r->reason != Reason::stopped &&
                       opt_.stop.memory_cap_bytes() > 0 && !opt_.stop.should_stop();
    if (!retry) return r;
    held_ = true;  // the workers finish what they plan and wait
    cv_.wait(lock, [&] { return busy_ == 0; });
    lock.unlock();
    r = plan(i, opt_.stop);
    lock.lock();
    held_ = false;
    cv_.notify_all();
    return r;
  }

 private:
  PlanResult plan(std::size_t i, const StopCondition& stop) const {
    return planner_.plan(uav_problem(sc_, opt_, ground_, i), sc_.world, stop);
  }
  void work() {
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      cv_.wait(lock, [&] { return quit_ || !held_; });
      if (quit_ || next_ >= n_) return;
      const std::size_t i = next_++;
      ++busy_;
      lock.unlock();
      std::optional<PlanResult> r;
      std::exception_ptr error;
      if (sc_.uavs[i].goal && !opt_.stop.should_stop()) {
        try {
          r = plan(i, share_);
        } catch (...) {
          error = std::current_exception();
        }
      }
      lock.lock();
      routes_[i] = std::move(r);
      errors_[i] = error;
      done_[i] = 1;
      --busy_;
      cv_.notify_all();
    }
  }

  const Scenario& sc_;
  const Planner& planner_;
  const MissionOptions& opt_;
  const GroundPoints& ground_;
  std::size_t n_;
  StopCondition share_;
  std::vector<std::optional<PlanResult>> routes_;
  std::vector<std::exception_ptr> errors_;
  std::vector<char> done_;
  std::mutex m_;
  std::condition_variable cv_;
  std::size_t next_ = 0;
  int busy_ = 0;
  bool held_ = false, quit_ = false;
  std::vector<std::thread> pool_;  // last: started after everything it uses
};

// Each UAV in the scenario's order: its route by the planner (RoutesAhead), then its departure:
// the earliest that keeps the separation from those timed before it (searched up to a minute
// plus twice the flights so far). UAVs without sensors also keep clear of the moving obstacles
// (known in advance to them); UAVs with sensors only plan to (they meet the moving obstacles in
// the loop). A stop leaves the UAVs done so far complete. With `give_up`, the first UAV that no
// delay places ends the timing: the UAVs after it keep their routes untimed, failed in conflict
// (the caller turns to space and time); returns whether it gave up.
bool plan_and_time(const Scenario& sc, const Planner& planner, const MissionOptions& opt, const GroundPoints& ground,
                   Plan& plan, bool give_up = false) {
  bool gave_up = false;
  plan.uavs.reserve(sc.uavs.size());  // `committed` points into it
  RoutesAhead routes(sc, planner, opt, ground);
  Committed committed;
  double horizon_s = 60.0;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    UavPlan& up = plan.uavs.emplace_back();
    up.id = u.id;
    if (opt.progress) opt.progress(i, sc.uavs.size());
    if (!u.goal) {
      up.message = "no goal given";
      up.reason = Reason::invalid;
      continue;
    }
    const std::optional<PlanResult> route = routes.take(i);
    if (!route) {
      up.message = kStoppedMessage;
      up.reason = Reason::stopped;
      continue;
    }
    const PlanResult& r = *route;
    up.status = r.status;
    up.reason = r.reason;
    up.message = r.message;
    up.stats = r.stats;
    up.waypoints = r.route.waypoints;
    up.route_length_m = r.route.length_m();
    if (up.status != Status::solved) continue;
    if (i < ground.start.size() && ground.start[i]) up.waypoints.insert(up.waypoints.begin(), *ground.start[i]);
    if (i < ground.goal.size() && ground.goal[i]) up.waypoints.push_back(*ground.goal[i]);
    up.route_length_m = Route{up.waypoints}.length_m();
    if (u.model && fly_route(u, up.waypoints, 0.0, opt.max_sample_dt_s, sc.mission.waypoints).empty()) {
      up.status = Status::failed;
      up.message =
          "its autopilot model cannot fly the route: it circles a waypoint (a turn tighter than its turn radius)";
      up.reason = Reason::no_route;
      continue;
    }
    horizon_s += 2.0 * up.route_length_m / u.speed.cruise_mps;
    if (gave_up && !senses(u) && !u.model) {  // space and time plans it
      up.status = Status::failed;
      up.reason = Reason::conflict;
      up.message = "not timed: an earlier UAV found no departure delay";
      continue;
    }
    Departure d = earliest_departure(sc, u, up.waypoints, horizon_s, committed, opt.delay_step_s, opt.max_sample_dt_s,
                                     opt.stop, senses(u) ? MovingObstacles::sensed : MovingObstacles::avoided);
    if (d.stopped) {
      up.status = Status::failed;
      up.message = kStoppedMessage;
      up.reason = Reason::stopped;
      continue;
    }
    if (!d.placed && senses(u)) {  // no clear departure planned: it departs at once and sees to it in the loop
      d.placed = true;
      d.trajectory = fly_route(u, up.waypoints, 0.0, opt.max_sample_dt_s, sc.mission.waypoints);
    }
    if (!d.placed) {
      up.status = Status::failed;
      up.reason = Reason::conflict;
      up.message = "conflicts with " + d.first.what + " for every departure delay up to " +
                   std::to_string(static_cast<int>(horizon_s)) + " s";
      gave_up = give_up;
      continue;
    }
    up.trajectory = std::move(d.trajectory);
    up.arrival_s = up.trajectory.back().t_s;
    committed.emplace_back(&u, &up);
  }
  if (opt.progress) opt.progress(sc.uavs.size(), sc.uavs.size());
  return gave_up;
}

// When a timed UAV departs: the end of its wait at the start.
double departure_s(const Trajectory& tr) { return tr.size() >= 2 && tr[1].p == tr[0].p ? tr[1].t_s : 0.0; }

// The UAVs with sensors, in the loop from their lift-off points to their touch-down points once
// they have climbed; the horizon three times the longest planned flight and two minutes more.
struct SensingUavs {
  std::vector<LoopUav> loop;
  std::vector<std::size_t> index;  // scenario index of each loop UAV
  std::vector<double> windows;
  double horizon_s = 0.0;
};

SensingUavs sensing_uavs(const Scenario& sc, const MissionContext& ctx, const Plan& plan, double window_m) {
  SensingUavs s;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    if (!senses(u) || plan.uavs[i].status != Status::solved) continue;
    std::vector<Vec3> route = plan.uavs[i].waypoints;
    double depart_s = departure_s(plan.uavs[i].trajectory);
    if (i < ctx.ground.start.size() && ctx.ground.start[i]) {
      route.erase(route.begin());
      depart_s += (route.front() - *ctx.ground.start[i]).norm() / u.speed.cruise_mps;
    }
    if (i < ctx.ground.goal.size() && ctx.ground.goal[i]) route.pop_back();
    s.loop.push_back({&u, std::move(route), *u.sensor_range_m, depart_s});
    s.index.push_back(i);
    s.windows.push_back(window_m > 0.0 ? window_m : *u.sensor_range_m);
    s.horizon_s = std::max(s.horizon_s, 120.0 + 3.0 * plan.uavs[i].trajectory.back().t_s);
  }
  return s;
}

// What each sensing UAV flew, also when it failed (the report shows it).
void record_flights(const Scenario& sc, const MissionContext& ctx, const SensingUavs& s, const LoopResult& flight,
                    const RollingWindow& controller, Plan& plan) {
  for (std::size_t k = 0; k < s.loop.size(); ++k) {
    UavPlan& up = plan.uavs[s.index[k]];
    const FlightState& f = flight.uavs[k];
    const RollingWindowLog& log = controller.log(k);
    const std::string buf = strf("flown in the loop (T = %g s): %d local replans, %d holds, %d escapes",
                                 sc.mission.step_s, log.replans, log.holds, log.escapes);
    up.stats.plan_ms += log.local_ms;  // wall time stays out of the plan's text (same bytes every run)
    up.trajectory = f.flown;
    if (!f.done) {
      up.status = Status::failed;
      up.reason = flight.stopped && ctx.options.stop.should_stop() ? Reason::stopped : Reason::no_route;
      up.message = "did not reach its goal by t=" + std::to_string(static_cast<int>(s.horizon_s)) + " s" +
                   (log.trouble.empty() ? "" : ": " + log.trouble);
      continue;
    }
    up.message = buf;
    up.waypoints = trajectory_corners(f.flown);
    up.route_length_m = Route{up.waypoints}.length_m();
    up.arrival_s = f.flown.back().t_s;
  }
}

// Against the truth: what they flew must keep clear of everything that moves.
void check_flown(const Scenario& sc, const Committed& committed, const SensingUavs& s, const RollingWindow& controller,
                 Plan& plan) {
  Committed all;
  for (const auto& c : committed)
    if (!senses(*c.first)) all.push_back(c);
  for (const std::size_t i : s.index)
    if (!plan.uavs[i].trajectory.empty()) all.emplace_back(&sc.uavs[i], &plan.uavs[i]);
  for (std::size_t k = 0; k < s.index.size(); ++k) {
    UavPlan& up = plan.uavs[s.index[k]];
    if (up.status != Status::solved) continue;
    Committed others;
    for (const auto& c : all)
      if (c.second != &up) others.push_back(c);
    const Conflict c = find_conflict(sc, sc.uavs[s.index[k]], up.trajectory, others);
    if (!c.any) continue;
    const std::string& trouble = controller.log(k).trouble;
    up.status = Status::failed;
    up.reason = Reason::conflict;
    up.message = "could not avoid " + c.what + (trouble.empty() ? "" : "; " + trouble);
  }
}

// The UAVs with sensors fly their routes in the loop, with the timed ones as objects to sense.
void fly_sensing(const Scenario& sc, const MissionContext& ctx, const LocalLayer& layer, const Committed& committed,
                 Plan& plan) {
  const MissionOptions& opt = ctx.options;
  const SensingUavs s = sensing_uavs(sc, ctx, plan, layer.window_m);
  if (s.loop.empty()) return;
  RollingWindowOptions rw;
  rw.step_s = sc.mission.step_s;
  rw.separation_m = sc.mission.separation_m;
  rw.local = layer.rrt;
  rw.seed = opt.seed;
  rw.stop = opt.stop;
  rw.via_points = sc.mission.waypoints;
  for (const auto& visit : ctx.ground.home_visits)  // a sortie from home passes its start and goal
    if (visit)
      for (const auto& p : {visit->start, visit->goal})
        if (p) rw.via_points.push_back(*p);
  std::vector<ScriptedUav> scripted;
  for (const auto& [spec, up] : committed)
    if (!senses(*spec)) scripted.push_back({spec, &up->trajectory});
  std::vector<std::string> ids;
  for (const std::size_t i : s.index) ids.push_back(sc.uavs[i].id);
  RollingWindow controller(sc.world, rw, s.windows, ids);
  LoopOptions lo;
  lo.step_s = sc.mission.step_s;
  lo.horizon_s = s.horizon_s;
  lo.max_sample_dt_s = opt.max_sample_dt_s;
  lo.separation_m = sc.mission.separation_m;
  const LoopResult flight = fly_closed_loop(sc.world, s.loop, scripted, controller, lo, opt.stop);
  record_flights(sc, ctx, s, flight, controller, plan);
  check_flown(sc, committed, s, controller, plan);
}

// Space and time for the timed UAVs: alone when asked for and no UAV senses (no route of the
// planner is needed), else over the delays' plan: replacing it when asked for, or in auto where
// delays left a UAV in conflict and space and time solve more of them.
void deconflict(const Scenario& sc, const MissionContext& ctx, const RoutesOptions& o, const Planner& planner,
                Plan& plan) {
  const std::vector<std::size_t> timed = timed_uavs(sc);
  const bool others =
      std::any_of(sc.uavs.begin(), sc.uavs.end(), [](const UavSpec& u) { return senses(u) || u.model; });
  if (o.deconfliction == Deconfliction::space_time && !others) {  // no route of the planner needed
    for (const UavSpec& u : sc.uavs) {
      UavPlan& up = plan.uavs.emplace_back();
      up.id = u.id;
      up.reason = Reason::invalid;
      up.message = "no goal given";
    }
    plan_space_time(sc, ctx, timed, o.space_time, plan);
    return;
  }
  const bool automatic = o.deconfliction == Deconfliction::automatic;
  if (plan_and_time(sc, planner, ctx.options, ctx.ground, plan, automatic)) {
    // Delays gave up at the first UAV they could not place: space and time, unless they solve
    // fewer than delays to the end.
    Plan together = plan;
    plan_space_time(sc, ctx, timed, o.space_time, together);
    if (solved_among(together, timed) == timed.size()) {
      plan = std::move(together);
      return;
    }
    plan.uavs.clear();
    plan_and_time(sc, planner, ctx.options, ctx.ground, plan);
    if (solved_among(together, timed) > solved_among(plan, timed)) {
      plan = std::move(together);
      return;
    }
    for (const std::size_t i : timed)
      if (plan.uavs[i].reason == Reason::conflict)
        plan.uavs[i].message += " (space and time together: " + together.uavs[i].message + ")";
    return;
  }
  const auto in_conflict = [&](std::size_t i) { return plan.uavs[i].reason == Reason::conflict; };
  if (o.deconfliction == Deconfliction::space_time) {
    plan_space_time(sc, ctx, timed, o.space_time, plan);
    return;
  }
  for (const std::size_t i : timed)  // delays, asked for
    if (in_conflict(i))
      plan.uavs[i].message += "; --set deconfliction=space_time plans the UAVs together in space and time";
}

}  // namespace

void RoutesMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const RoutesOptions o = routes_options(ctx);
  // A spacing the lattice cannot hold is the parameter's fault, said before anything is planned.
  if (o.space_time.cell_m > 0.0 && lattice_cell_count(sc.world.bounds(), o.space_time.cell_m) >
                                       static_cast<std::uint64_t>(SpaceTimeTable::kMostVertices))
    throw std::invalid_argument("planner.params.space_time_cell_m: " + num_text(o.space_time.cell_m) +
                                " m makes a space-time lattice of more than " +
                                std::to_string(SpaceTimeTable::kMostVertices) + " cells over the world's bounds");
  const auto planner = make_planner(ctx.algorithm, ctx.params);
  deconflict(sc, ctx, o, *planner, plan);
  Committed committed;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i)
    if (!senses(sc.uavs[i]) && plan.uavs[i].status == Status::solved)
      committed.emplace_back(&sc.uavs[i], &plan.uavs[i]);
  fly_sensing(sc, ctx, o.local, committed, plan);
}

}  // namespace uavplan
