#include "uavplan/coordination/routes/space_time_routes.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/routes/route_problem.h"
#include "uavplan/coordination/spacetime/cbs.h"
#include "uavplan/coordination/spacetime/prioritized.h"
#include "uavplan/coordination/spacetime/uav_lattice.h"
#include "uavplan/coordination/timing.h"
#include "uavplan/core/text.h"

namespace uavplan {
namespace {

constexpr double kEcbsW = 1.3;              // ECBS's bound, as in the grid benchmark
constexpr std::uint64_t kEcbsNodes = 2000;  // high-level nodes ECBS may open after prioritised planning
constexpr int kOrders = 8;                  // prioritised planning's orders

// What the lattice is built for: the UAVs' largest separation and body, smallest climb limit,
// ceiling and cruise speed.
struct Fleet {
  double need_m = 0.0, body_m = 0.0, climb_rad = kPi / 2, ceiling_z = World::kInf, speed_mps = World::kInf;
};

Fleet fleet_of(const Scenario& sc, const std::vector<std::size_t>& which) {
  Fleet f;
  for (const std::size_t i : which) {
    const UavSpec& a = sc.uavs[i];
    for (const std::size_t j : which)
      if (j != i) f.need_m = std::max(f.need_m, required_separation_m(sc, a, sc.uavs[j]));
    f.body_m = std::max(f.body_m, keep_off_m(a));
    f.climb_rad = std::min(f.climb_rad, a.max_climb_rad);
    if (a.ceiling_m) f.ceiling_z = std::min(f.ceiling_z, *a.ceiling_m);
    f.speed_mps = std::min(f.speed_mps, a.speed.cruise_mps);
  }
  f.need_m += kTimingMargin_m;
  return f;
}

// The UAVs' own points (starts, via points, goals), each once.
struct Points {
  std::vector<Vec3> at;
  int add(const Vec3& p) {
    const auto it = std::find(at.begin(), at.end(), p);
    if (it != at.end()) return static_cast<int>(it - at.begin());
    at.push_back(p);
    return static_cast<int>(at.size()) - 1;
  }
};

struct Flights {
  Points points;
  std::vector<int> start;                 // point per UAV of `which`
  std::vector<std::vector<int>> targets;  // points per UAV of `which`
};

Flights flights_of(const Scenario& sc, const MissionContext& ctx, const std::vector<std::size_t>& which) {
  Flights f;
  for (const std::size_t i : which) {
    const Problem pb = uav_problem(sc, ctx.options, ctx.ground, i);
    f.start.push_back(f.points.add(sc.uavs[i].start));
    std::vector<int> t;
    for (const Vec3& v : pb.via) t.push_back(f.points.add(v));
    t.push_back(f.points.add(pb.goal));
    f.targets.push_back(std::move(t));
  }
  return f;
}

void fail(UavPlan& up, Reason why, std::string message) {
  up.status = Status::failed;
  up.reason = why;
  up.message = std::move(message);
  up.trajectory.clear();
  up.waypoints.clear();
}

// Appends a straight piece to `to` over dt_s, in rows at most max_dt_s apart.
void append_piece(Trajectory& tr, const Vec3& to, double dt_s, double max_dt_s) {
  const TrajectorySample from = tr.back();
  const int n = std::max(1, static_cast<int>(std::ceil(dt_s / max_dt_s - kWholeNumberSlack)));
  for (int s = 1; s <= n; ++s) {
    const double f = static_cast<double>(s) / n;
    tr.push_back({from.t_s + f * dt_s, from.p + f * (to - from.p)});
  }
}

// Timing shared by every UAV: the lattice's first tick, after the longest climb from the ground.
struct Clock {
  double t0_s = 0.0, tick_s = 1.0, max_dt_s = 1.0;
};

// UAV i's flight: on the ground or at its start until its climb ends at t0, the path a tick a move,
// then its descent to the ground.
Trajectory flight_of(const Scenario& sc, const MissionContext& ctx, std::size_t i, const UavLattice& l,
                     const SpaceTimePath& path, const Clock& c) {
  const UavSpec& u = sc.uavs[i];
  const std::optional<Vec3> ground_start = i < ctx.ground.start.size() ? ctx.ground.start[i] : std::nullopt;
  const std::optional<Vec3> ground_goal = i < ctx.ground.goal.size() ? ctx.ground.goal[i] : std::nullopt;
  Trajectory tr;
  const Vec3 lift = l.position[path.front()];
  if (ground_start) {
    const double climb_s = (lift - *ground_start).norm() / u.speed.cruise_mps;
    tr.push_back({0.0, *ground_start});
    if (c.t0_s - climb_s > 0.0) tr.push_back({c.t0_s - climb_s, *ground_start});
    append_piece(tr, lift, c.t0_s - tr.back().t_s, c.max_dt_s);
  } else {
    tr.push_back({0.0, lift});
    if (c.t0_s > 0.0) append_piece(tr, lift, c.t0_s, c.max_dt_s);
  }
  for (std::size_t k = 1; k < path.size(); ++k) append_piece(tr, l.position[path[k]], c.tick_s, c.max_dt_s);
  if (ground_goal) {
    const double descent_s = (tr.back().p - *ground_goal).norm() / u.speed.cruise_mps;
    append_piece(tr, *ground_goal, descent_s, c.max_dt_s);
  }
  return tr;
}

MapfResult solve(const LatticeAgents& agents, MapfMethod method, const StopCondition& stop) {
  switch (method) {
    case MapfMethod::prioritized:
      return solve_prioritized(agents, kOrders, stop);
    case MapfMethod::ecbs:
      return solve_cbs(agents, kEcbsW, stop);
    case MapfMethod::cbs:
      return solve_cbs(agents, 1.0, stop);
    case MapfMethod::automatic:
      break;
  }
  MapfResult quick = solve_prioritized(agents, kOrders, stop);
  if (quick.solved() || stop.should_stop()) return quick;
  MapfResult bounded = solve_cbs(agents, kEcbsW, stop, kEcbsNodes);
  bounded.low_level_expansions += quick.low_level_expansions;
  if (!bounded.solved()) bounded.message = quick.message + "; then ECBS: " + bounded.message;
  return bounded;
}

// The solved UAVs of the plan outside `which` (flown by their own rules: an autopilot model).
Committed planned_before(const Scenario& sc, const std::vector<std::size_t>& which, const Plan& plan) {
  Committed out;
  for (std::size_t i = 0; i < plan.uavs.size() && i < sc.uavs.size(); ++i)
    if (plan.uavs[i].status == Status::solved && !plan.uavs[i].trajectory.empty() &&
        std::find(which.begin(), which.end(), i) == which.end() && !sc.uavs[i].sensor_range_m)
      out.emplace_back(&sc.uavs[i], &plan.uavs[i]);
  return out;
}

// Each solved UAV checked as the verifier checks it, in scenario order against those before:
// separation (and moving obstacles), turn and climb limits, the mission's own rules.
void check_flights(const Scenario& sc, const std::vector<std::size_t>& which, const UavLattice& l,
                   const std::vector<SpaceTimePath>& paths, Plan& plan) {
  const Mission* mission = find_mission(sc.mission.type);
  Committed committed = planned_before(sc, which, plan);
  for (std::size_t k = 0; k < which.size(); ++k) {
    const std::size_t i = which[k];
    UavPlan& up = plan.uavs[i];
    if (up.status != Status::solved) continue;
    const UavSpec& u = sc.uavs[i];
    const Conflict c = find_conflict(sc, u, up.trajectory, committed);
    if (c.any) {
      fail(up, Reason::conflict, "space-time plan conflicts with " + c.what);
      continue;
    }
    Violations v;
    std::vector<Vec3> air;  // the route in the air (take-off and landing legs are vertical)
    for (const int x : paths[k])
      if (air.empty() || air.back() != l.position[x]) air.push_back(l.position[x]);
    for (const LimitViolation& lv : check_route_limits(air, u)) {
      fail(up, Reason::no_route,
           std::string("its space-time route breaks its ") +
               (lv.kind == LimitViolation::Kind::turn ? "turn" : "climb") + " limit (" +
               num_text(rad_to_deg(lv.value_rad)) + " deg): the lattice's moves turn by 45 deg steps");
      break;
    }
    if (up.status != Status::solved) continue;
    if (mission) mission->check_uav(sc, u, up.trajectory, v);
    if (!v.empty()) {
      fail(up, Reason::no_route, "its space-time route misses a rule of the mission: " + v.front().message);
      continue;
    }
    committed.emplace_back(&u, &up);
  }
}

// The lattice over the view's world and the UAVs `which` on it, with the clock of their flights;
// or why there is none (`problem`, with its reason).
struct Layer {
  Fleet fleet;
  std::unique_ptr<UavLattice> lattice;
  std::unique_ptr<LatticeAgents> agents;  // points into *lattice
  Clock clock;
  Reason why = Reason::none;
  std::string problem;
};

Layer make_layer(const Scenario& sc, const MissionContext& ctx, const std::vector<std::size_t>& which,
                 const SpaceTimeRoutesOptions& o, const Plan& plan) {
  Layer layer;
  layer.fleet = fleet_of(sc, which);
  const Flights flights = flights_of(sc, ctx, which);
  UavLatticeOptions lo;
  lo.cell_m = o.cell_m;
  lo.body_m = layer.fleet.body_m;
  lo.need_m = layer.fleet.need_m;
  lo.max_climb_rad = layer.fleet.climb_rad;
  lo.ceiling_z = layer.fleet.ceiling_z;
  const StopCondition& stop = ctx.options.stop;
  try {
    layer.lattice = std::make_unique<UavLattice>(build_uav_lattice(sc.world, flights.points.at, lo, stop));
    std::vector<LatticeAgent> list;
    for (std::size_t k = 0; k < which.size(); ++k) {
      const UavSpec& u = sc.uavs[which[k]];
      LatticeAgent a{layer.lattice->point_vertex(flights.start[k]),
                     {},
                     u.max_turn_rad,
                     u.heading_rad ? heading_vector(*u.heading_rad) : Vec3::Zero()};
      for (const int t : flights.targets[k]) a.targets.push_back(layer.lattice->point_vertex(t));
      list.push_back(std::move(a));
    }
    layer.agents = std::make_unique<LatticeAgents>(*layer.lattice, std::move(list), layer.fleet.need_m, stop.threads());
  } catch (const std::exception& e) {
    layer.why = stop.should_stop() ? Reason::stopped : Reason::invalid;
    layer.problem = stop.should_stop() ? kStoppedMessage : std::string("space-time deconfliction: ") + e.what();
    return layer;
  }
  const std::string cell = strf("%.3g m", layer.lattice->cell_m);
  for (std::size_t k = 0; k < which.size() && layer.problem.empty(); ++k)
    if (!layer.agents->reachable(static_cast<int>(k))) {
      layer.why = Reason::no_route;
      layer.problem = "space-time deconfliction: UAV '" + sc.uavs[which[k]].id +
                      "' has no route on the lattice (cells of " + cell +
                      "); a smaller space_time_cell_m may find a way";
    }
  layer.clock.tick_s = layer.lattice->longest_edge_m / layer.fleet.speed_mps;
  layer.clock.max_dt_s = ctx.options.max_sample_dt_s;
  double radius_m = 0.0;
  for (const std::size_t i : which) {
    radius_m = std::max(radius_m, sc.uavs[i].radius_m);
    if (i < ctx.ground.start.size() && ctx.ground.start[i])
      layer.clock.t0_s =
          std::max(layer.clock.t0_s, (sc.uavs[i].start - *ctx.ground.start[i]).norm() / sc.uavs[i].speed.cruise_mps);
  }
  // Known in advance to UAVs without sensors (find_conflict keeps their radius off the surface),
  // and so are the UAVs planned already: each a moving obstacle as wide as keeps the separation.
  std::vector<MovingObstacle> moving = sc.world.moving();
  for (const auto& [spec, flown] : planned_before(sc, which, plan)) {
    MovingObstacle m{spec->id, 0.0, Vec3::Zero(), Vec3::Zero(), {}};
    for (const std::size_t i : which)
      m.radius_m = std::max(m.radius_m, required_separation_m(sc, *spec, sc.uavs[i]) - radius_m);
    for (const TrajectorySample& r : flown->trajectory) m.path.push_back({r.t_s, r.p});
    moving.push_back(std::move(m));
  }
  layer.agents->keep_off_moving(moving, radius_m + kTimingMargin_m, layer.clock.t0_s, layer.clock.tick_s);
  return layer;
}

}  // namespace

void plan_space_time(const Scenario& sc, const MissionContext& ctx, const std::vector<std::size_t>& which,
                     const SpaceTimeRoutesOptions& o, Plan& plan) {
  if (which.empty()) return;
  const auto fail_all = [&](Reason why, const std::string& message) {
    for (const std::size_t i : which) fail(plan.uavs[i], why, message);
  };
  const Layer layer = make_layer(sc, ctx, which, o, plan);
  if (!layer.problem.empty()) return fail_all(layer.why, layer.problem);
  const StopCondition& stop = ctx.options.stop;
  const MapfResult r = solve(*layer.agents, o.method, stop);
  if (!r.solved()) {
    if (stop.should_stop()) return fail_all(Reason::stopped, kStoppedMessage);
    return fail_all(Reason::conflict, "space-time deconfliction found no conflict-free plan (" + r.message +
                                          "); try --set space_time_method=cbs or another space_time_cell_m");
  }
  const std::string how = strf("space-time deconfliction: %s; lattice %.3g m, tick %.3g s", r.method.c_str(),
                               layer.lattice->cell_m, layer.clock.tick_s);
  for (std::size_t k = 0; k < which.size(); ++k) {
    UavPlan& up = plan.uavs[which[k]];
    up.status = Status::solved;
    up.reason = Reason::none;
    up.message = how;
    up.trajectory = flight_of(sc, ctx, which[k], *layer.lattice, r.paths[k], layer.clock);
    up.waypoints = trajectory_corners(up.trajectory);
    up.route_length_m = Route{up.waypoints}.length_m();
    up.arrival_s = up.trajectory.back().t_s;
    up.stats.nodes_expanded = r.low_level_expansions;
    up.stats.grid_cells = static_cast<std::uint64_t>(layer.lattice->cell_count());
    up.stats.cell_m = layer.lattice->cell_m;
  }
  check_flights(sc, which, *layer.lattice, r.paths, plan);
}

std::vector<LoneFlight> lone_space_time_flights(const Scenario& sc, const MissionContext& ctx,
                                                const std::vector<std::size_t>& which,
                                                const SpaceTimeRoutesOptions& o) {
  std::vector<LoneFlight> out(which.size());
  const Layer layer = make_layer(sc, ctx, which, o, Plan{});
  if (!layer.agents) return out;
  SpaceTimeSearches search;
  SpaceTimeTable none;
  none.clear(layer.lattice->graph.vertex_count);
  for (std::size_t k = 0; k < which.size(); ++k) {
    const SpaceTimeAnswer a = layer.agents->plan(static_cast<int>(k), none, nullptr, 1.0, search, ctx.options.stop);
    if (!a.found) continue;
    const Trajectory tr = flight_of(sc, ctx, which[k], *layer.lattice, a.path, layer.clock);
    out[k] = {true, tr.back().t_s, flown_length_m(tr)};
  }
  return out;
}

}  // namespace uavplan
