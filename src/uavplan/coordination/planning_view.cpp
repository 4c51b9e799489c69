#include "uavplan/coordination/planning_view.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/core/text.h"

namespace uavplan {
namespace {

// The world with its ground raised by `by_m`: terrain heights plus it, and a floor over the
// bottom of the bounds.
World raised(const World& w, double by_m) {
  WorldSpec s = w.spec();
  const Aabb& b = s.bounds;
  if (const auto& t = s.terrain) {
    std::vector<double> h, lows;
    for (int j = 0; j < t->ny(); ++j)
      for (int i = 0; i < t->nx(); ++i) {
        h.push_back(t->height(i, j) + by_m);
        if (t->has_lows()) lows.push_back(t->low(i, j) + by_m);
      }
    s.terrain = TerrainGrid(t->origin(), t->cell_m(), t->nx(), t->ny(), std::move(h), std::move(lows));
  }
  s.obstacles.push_back(
      Box{Vec3(b.min.x() - 1, b.min.y() - 1, b.min.z() - 1), Vec3(b.max.x() + 1, b.max.y() + 1, b.min.z() + by_m)});
  return World(std::move(s));
}

// The sky more than `agl_m` above terrain `t` closed: a box over each of its cells (from its lowest
// ground: max_agl is measured from what is below) and over the
// floor beside the grid, from that height to above the bounds (without terrain: a ceiling). Where
// the band's top is above the bounds there is nothing to close: no box.
void close_sky(WorldSpec& s, const TerrainGrid& t, double agl_m) {
  const Aabb& b = s.bounds;
  const double top = b.max.z() + 1.0, floor = b.min.z() + agl_m;
  const std::size_t first = s.obstacles.size();
  const double c = t.cell_m(), x0 = t.origin().x(), y0 = t.origin().y();
  const double x1 = x0 + t.nx() * c, y1 = y0 + t.ny() * c;
  const auto add = [&](const Box& box) {
    if (box.max.x() > box.min.x() && box.max.y() > box.min.y() && box.max.z() > box.min.z()) s.obstacles.push_back(box);
  };
  for (int j = 0; j < t.ny(); ++j)
    for (int i = 0; i < t.nx(); ++i)
      add(Box{Vec3(x0 + i * c, y0 + j * c, std::max(t.low(i, j), b.min.z()) + agl_m),
              Vec3(x0 + (i + 1) * c, y0 + (j + 1) * c, top)});
  // Beside the grid: four strips over the floor.
  const Vec3 lo(b.min.x() - 1, b.min.y() - 1, floor), hi(b.max.x() + 1, b.max.y() + 1, top);
  for (const Box& strip :
       {Box{lo, Vec3(x0, hi.y(), top)}, Box{Vec3(x1, lo.y(), floor), hi},
        Box{Vec3(x0, lo.y(), floor), Vec3(x1, y0, top)}, Box{Vec3(x0, y1, floor), Vec3(x1, hi.y(), top)}})
    add(strip);
  s.obstacle_ids.resize(first);  // named for the planners' messages
  s.obstacle_ids.resize(s.obstacles.size(), "above max_agl");
}

// Moving obstacles as seen from a clock `shift_s` later.
void shift_moving(WorldSpec& s, double shift_s) {
  for (MovingObstacle& m : s.moving) {
    if (m.path.empty()) {
      m.position += shift_s * m.velocity_mps;
    } else {
      for (TimedPoint& r : m.path) r.t_s -= shift_s;
      m.position = m.path.front().p;
    }
  }
}

}  // namespace

namespace {

// Whether a UAV with a home at `home` climbs from it straight to `p` (or descends from p straight
// to it): p is on home's vertical column (World::same_column, as the verifier), above the
// lift-off height, and the column up to p is clear of obstacles. Then the take-off ends at p, not
// at the lift-off height below it: a leg straight up or down is not one a planner with turn and
// climb limits can fly.
bool climbs_straight_to(const Scenario& sc, const UavSpec& u, const Vec3& home, const Vec3& p, double lift_m) {
  if (!World::same_column(p, home) || p.z() < home.z() + lift_m) return false;
  return vertical_column_problem(sc, u, home, p.z() - sc.world.ground_z(home.x(), home.y())).empty();
}

}  // namespace

std::vector<PlacementProblem> placement_problems(const Scenario& sc) {
  std::vector<PlacementProblem> out(sc.uavs.size());
  const PlanningView v = planning_view(sc, GroundLegTiming::shifted, BandTop::open);  // the band: below
  const Scenario& planned = v.identity ? sc : v.scenario;
  const double agl = planning_min_agl_m(sc);
  const std::optional<double> top = planning_max_agl_m(sc);
  auto check = [&](const UavSpec& u, const UavSpec& pu, const Vec3& p, const Vec3& pp) -> std::string {
    if (sc.world.on_ground(p))
      return ground_column_problem(sc, u, Vec3(pp.x(), pp.y(), sc.world.ground_z(pp.x(), pp.y())));
    const double keep = keep_off_m(u);
    // Over terrain the planners keep the body under the band's top, over a floor the centre.
    if (top) {
      const double high = sc.world.highest_height_above_ground(p, p);
      const double limit = *top - (sc.world.terrain() ? keep : 0.0);
      if (high > limit)
        return num_text(high) + " m above the ground, above " +
               (sc.world.terrain() ? "max_agl less radius and clearance " : "max_agl ") + num_text(limit) +
               " m (planners keep the smallest max_agl of the scenario, " + num_text(*top) + " m, for every UAV)";
    }
    const double h = sc.world.lowest_height_above_ground(p, p);
    if (agl > 0.0 && h < agl + keep)
      return num_text(h) + " m above the ground, below min_agl plus radius and clearance " + num_text(agl + keep) +
             " m (planners keep the largest min_agl of the scenario, " + num_text(agl) + " m, for every UAV)";
    if (planned.world.clearance(pp, pu.radius_m) < pu.radius_m)
      return "within " + num_text(keep) + " m (radius plus clearance) of an obstacle or the terrain" +
             (agl > 0.0 ? " raised by min_agl " + num_text(agl) + " m" : std::string());
    return {};
  };
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    const UavSpec& pu = planned.uavs[i];
    out[i].start = check(u, pu, u.start, pu.start);
    if (u.goal && pu.goal) out[i].goal = check(u, pu, *u.goal, *pu.goal);
  }
  return out;
}

PlanningView planning_view(const Scenario& sc, GroundLegTiming timing, BandTop band_top) {
  PlanningView v;
  const std::size_t n = sc.uavs.size();
  v.lift_off.assign(n, std::nullopt);
  v.touch_down.assign(n, std::nullopt);
  v.ground.start.assign(n, std::nullopt);
  v.ground.goal.assign(n, std::nullopt);
  v.ground.home_visits.assign(n, std::nullopt);
  const double agl = planning_min_agl_m(sc);
  const std::optional<double> top = planning_max_agl_m(sc);
  bool bodies = false;
  for (const UavSpec& u : sc.uavs) bodies = bodies || u.clearance_m > 0.0;
  const World& w = sc.world;
  const std::vector<Arrival> arrivals = arrival_points(sc);
  std::vector<std::optional<Vec3>> goal(n);
  bool moved = false;
  for (std::size_t i = 0; i < n; ++i) {
    v.arrival_problem.push_back(arrivals[i].problem);
    if (sc.uavs[i].goal) goal[i] = arrivals[i].tolerance_m > 0.0 ? arrivals[i].point : *sc.uavs[i].goal;
    moved = moved || arrivals[i].tolerance_m > 0.0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const UavSpec& u = sc.uavs[i];
    const double lift = lift_height_m(sc, u);
    if (u.home && goal[i]) {  // up from home, its start and goal on the way, down at home
      const bool up_to_start = climbs_straight_to(sc, u, *u.home, u.start, lift);
      const bool down_from_goal = climbs_straight_to(sc, u, *u.home, *goal[i], lift);
      v.lift_off[i] = up_to_start ? u.start : *u.home + Vec3(0, 0, lift);
      v.touch_down[i] = down_from_goal ? *goal[i] : *u.home + Vec3(0, 0, lift);
      v.ground.start[i] = v.ground.goal[i] = *u.home;
      GroundPoints::HomeVisits visit;
      if (!up_to_start) visit.start = u.start;
      if (!down_from_goal) visit.goal = *goal[i];
      v.ground.home_visits[i] = visit;
      if (timing == GroundLegTiming::shifted)
        v.takeoff_s = std::max(v.takeoff_s, (v.lift_off[i]->z() - u.home->z()) / u.speed.cruise_mps);
      continue;
    }
    if (w.on_ground(u.start)) {
      v.lift_off[i] = Vec3(u.start.x(), u.start.y(), w.ground_z(u.start.x(), u.start.y()) + lift);
      v.ground.start[i] = u.start;
      if (timing == GroundLegTiming::shifted) v.takeoff_s = std::max(v.takeoff_s, lift / u.speed.cruise_mps);
    }
    if (goal[i] && w.on_ground(*goal[i])) {
      const double g = w.ground_z(goal[i]->x(), goal[i]->y());
      v.touch_down[i] = Vec3(goal[i]->x(), goal[i]->y(), g + lift);
      v.ground.goal[i] = Vec3(goal[i]->x(), goal[i]->y(), g);
    }
  }
  const bool lifted =
      std::any_of(v.lift_off.begin(), v.lift_off.end(), [](const auto& p) { return p.has_value(); }) ||
      std::any_of(v.touch_down.begin(), v.touch_down.end(), [](const auto& p) { return p.has_value(); });
  if (agl <= 0.0 && !top && !bodies && !lifted && !moved) return v;
  v.identity = false;
  v.scenario = sc;
  WorldSpec spec = (agl > 0.0 ? raised(w, agl) : w).spec();
  if (top && w.terrain() && band_top == BandTop::closed)
    close_sky(spec, *w.terrain(), *top);  // over the terrain as it is, not raised
  shift_moving(spec, v.takeoff_s);
  v.scenario.world = World(std::move(spec));
  for (std::size_t i = 0; i < n; ++i) {
    UavSpec& u = v.scenario.uavs[i];
    u.radius_m = keep_off_m(u);
    u.clearance_m = 0.0;
    u.min_agl_m = 0.0;
    if (top && !w.terrain())
      u.ceiling_m = std::min(u.ceiling_m.value_or(w.bounds().max.z()), w.bounds().min.z() + *top);
    u.max_agl_m.reset();
    if (v.lift_off[i]) {
      u.start = *v.lift_off[i];
      u.heading_rad.reset();  // a vertical take-off can leave in any direction
    }
    u.goal = v.touch_down[i] ? v.touch_down[i] : goal[i];
  }
  return v;
}

namespace {

// Straight from the last row to `to` at speed v_mps, rows at most max_dt_s apart.
void fly_to(Trajectory& tr, const Vec3& to, double v_mps, double max_dt_s) {
  const Vec3 from = tr.back().p;
  const double t0 = tr.back().t_s, dur = (to - from).norm() / v_mps;
  const int pieces = std::max(1, static_cast<int>(std::ceil(dur / max_dt_s - kWholeNumberSlack)));
  for (int k = 1; k <= pieces; ++k)
    tr.push_back({t0 + dur * k / pieces, k == pieces ? to : Vec3(from + (to - from) * k / pieces)});
}

// The take-off of a trajectory that begins at its lift-off point: a wait there long enough is
// the climb (on the ground until it), else the climb comes first and the rest `shift_s` later.
Trajectory with_takeoff(const Trajectory& flown, const Vec3& ground, double v_mps, double shift_s, double max_dt_s) {
  const Vec3 lift = flown.front().p;
  const double climb_s = (lift - ground).norm() / v_mps;
  std::size_t held = 0;
  while (held + 1 < flown.size() && flown[held + 1].p == lift) ++held;
  const double hold_s = flown[held].t_s - flown.front().t_s;
  const bool in_wait = hold_s >= climb_s - kSameTime_s;
  const double shift = in_wait ? 0.0 : (shift_s > 0.0 ? shift_s : climb_s);
  const double lift_s = in_wait ? flown[held].t_s : shift;
  Trajectory tr{{0.0, ground}};
  if (lift_s - climb_s > 1e-12) tr.push_back({lift_s - climb_s, ground});
  fly_to(tr, lift, v_mps, max_dt_s);
  tr.back().t_s = lift_s;  // the same instant, without rounding
  for (std::size_t k = in_wait ? held + 1 : 1; k < flown.size(); ++k) tr.push_back({flown[k].t_s + shift, flown[k].p});
  return tr;
}

}  // namespace

void to_scenario(const PlanningView& v, const Scenario& sc, Plan& plan, double max_dt_s) {
  if (v.identity) return;
  for (std::size_t i = 0; i < plan.uavs.size() && i < sc.uavs.size(); ++i) {
    UavPlan& up = plan.uavs[i];
    if (up.trajectory.empty()) continue;
    const double v_mps = sc.uavs[i].speed.cruise_mps;
    bool changed = false;
    if (v.lift_off[i] && (up.trajectory.front().p - *v.lift_off[i]).norm() <= kSamePoint_m) {
      up.trajectory = with_takeoff(up.trajectory, *v.ground.start[i], v_mps, v.takeoff_s, max_dt_s);
      up.waypoints.insert(up.waypoints.begin(), *v.ground.start[i]);
      changed = true;
    } else if (v.takeoff_s > 0.0 && !v.lift_off[i]) {
      for (TrajectorySample& s : up.trajectory) s.t_s += v.takeoff_s;
      up.trajectory.insert(up.trajectory.begin(), {0.0, up.trajectory.front().p});
    }
    if (v.touch_down[i] && (up.trajectory.back().p - *v.touch_down[i]).norm() <= 1e-6) {
      fly_to(up.trajectory, *v.ground.goal[i], v_mps, max_dt_s);
      up.waypoints.push_back(*v.ground.goal[i]);
      changed = true;
    }
    if (changed) up.route_length_m = Route{up.waypoints}.length_m();
    up.arrival_s = up.trajectory.back().t_s;
  }
}

}  // namespace uavplan
