// P4's directional A* as a planner: its options, the query of a problem, the lattice's memory,
// one search per leg through via points. The search is directional_search.cpp, the cone tables
// directional_cones.cpp, what they share directional_lattice.h.
#include "uavplan/planning/search/directional_astar.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

#include "uavplan/core/text.h"
#include "uavplan/planning/grid_budget.h"
#include "uavplan/planning/search/directional_lattice.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

using namespace directional;

DirectionalAStarOptions DirectionalAStarOptions::from_params(const Params& params) {
  ParamReader r(params, "directional_astar");
  DirectionalAStarOptions o = read(r);
  r.finish();
  return o;
}

DirectionalAStarOptions DirectionalAStarOptions::read(ParamReader& r) {
  DirectionalAStarOptions o;
  o.cell_m = r.number("cell_m", o.cell_m, 0.0, 1e9, "lattice spacing, m; 0: derived from the world");
  o.step_cells = r.number("step_cells", o.step_cells, 0.0, 100.0,
                          "L, the step in cells; 0: max(2.5, 2 / psi_max, in 3-D 1 / tan(phi_max))");
  r.require(o.step_cells == 0.0 || o.step_cells >= 0.5, "step_cells", "must be 0 (derived) or at least 0.5");
  o.directions =
      r.integer("directions", o.directions, 1, 64, "M, the directions of the cone for yaw and (in 3-D) pitch");
  o.max_yaw_rad = deg_to_rad(r.number("max_yaw_deg", rad_to_deg(o.max_yaw_rad), 0.0, 180.0,
                                      "psi_max, deg; 0: the UAV's max_turn (60 if it has none)"));
  o.max_pitch_rad = deg_to_rad(r.number("max_pitch_deg", rad_to_deg(o.max_pitch_rad), 0.0, 90.0,
                                        "phi_max, deg; 0: the UAV's max_climb (30 if it has none)"));
  o.max_expansions = r.count("max_expansions", o.max_expansions, 1, 1'000'000'000,
                             "the search gives up (budget) after this many expansions");
  o.target_points =
      r.count("target_points", o.target_points, 1, 1'000'000'000, "a derived lattice has about this many points");
  o.step_cells_max = r.number("step_cells_max", o.step_cells_max, 0.5, 100.0, "the longest derived step, in cells");
  o.min_turn_radius_m = r.number("min_turn_radius_m", o.min_turn_radius_m, 0.0, 1e9,
                                 "the least radius of a turn, m (0: none beyond the yaw limit)");
  o.heuristic_weight =
      r.number("heuristic_weight", o.heuristic_weight, 1.0, 10.0, "w in f = g + w h; above 1 trades length for speed");
  o.climb_bound = r.boolean("climb_bound", o.climb_bound, "bound the heuristic by the climb limit (exact in 3-D)");
  o.relaxed_heuristic = r.boolean("relaxed_heuristic", o.relaxed_heuristic,
                                  "the heuristic from a reverse search without the turn limits");
  o.incumbent_weight = r.number("incumbent_weight", o.incumbent_weight, 1.0, 10.0,
                                "a first search at this weight bounds the exact one (1: none)");
  return o;
}

// L when the scenario gives none: max(2.5, 2 / psi_max) (lattice directions L cells away are about
// 1 / L rad apart, so a finer turn limit needs a longer step to turn at all), and in 3-D at least
// 1 / tan(phi_max), rounded up to a tenth: the least climb of a move, one cell in L, must keep the
// climb limit, or the search could never change height (15 deg: 3.8 cells).
namespace {

double default_step_cells(const World& world, const DirectionalQuery& q) {
  double l = std::max(2.5, 2.0 / q.max_yaw_rad);
  if (make_lattice(world, q).n[2] > 1 && q.max_pitch_rad < kPi / 2 - kUnlimitedAngleSlack_rad)
    l = std::max(l, std::ceil(10.0 / std::tan(q.max_pitch_rad) - kWholeNumberSlack) / 10.0);
  return l;
}

}  // namespace

DirectionalQuery DirectionalAStarPlanner::query_for(const Problem& pb, const World& world) const {
  const UavSpec& u = pb.uav;
  DirectionalQuery q;
  q.start = u.start;
  q.goal = pb.goal;
  q.heading_rad = u.heading_rad;
  q.cell_m = options_.cell_m > 0.0 ? options_.cell_m : derived_cell(world, options_.target_points);
  q.directions = options_.directions;
  const double uav_yaw = u.max_turn_rad < kPi - kUnlimitedAngleSlack_rad ? u.max_turn_rad : kDefaultYaw_rad;
  const double uav_pitch = u.max_climb_rad < kPi / 2 - kUnlimitedAngleSlack_rad ? u.max_climb_rad : kDefaultPitch_rad;
  q.max_yaw_rad = options_.max_yaw_rad > 0.0 ? std::min(options_.max_yaw_rad, u.max_turn_rad) : uav_yaw;
  q.max_pitch_rad = options_.max_pitch_rad > 0.0 ? std::min(options_.max_pitch_rad, u.max_climb_rad) : uav_pitch;
  q.step_cells = options_.step_cells > 0.0 ? options_.step_cells : default_step_cells(world, q);
  const SegmentRule rule(world, u);
  q.inflation_m = rule.inflation_m();
  q.ceiling_m = rule.ceiling_m();
  q.max_expansions = options_.max_expansions;
  q.heuristic_weight = options_.heuristic_weight;
  q.climb_bound = options_.climb_bound;
  q.relaxed_heuristic = options_.relaxed_heuristic;
  q.incumbent_weight = options_.incumbent_weight;
  return q;
}

void DirectionalAStarPlanner::require_lattice(const World& world, const DirectionalQuery& q, int engines,
                                              const StopCondition& stop) {
  const Vec3 ext = world.bounds().extent();
  double points = 1.0;
  for (int a = 0; a < 3; ++a) points *= 1.0 + std::floor(ext[a] / q.cell_m + kWholeNumberSlack);
  const std::string what = strf("planner.params.cell_m = %g m", q.cell_m);
  // Per lattice point: a cached clearance (4 bytes), search nodes (16 bytes) for up to 8
  // heading sectors and the relaxed heuristic's distance and flag (9 bytes), per engine.
  require_grid(points * 8.0, engines * ((4.0 + 9.0) / 8.0 + 16.0), stop, what);
}

// Through via points, one search per leg on the same lattice and engine: each leg starts with the
// heading its previous leg arrived with, so the turn at a via point keeps the limit too.
PlanResult DirectionalAStarPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult res;
  std::vector<Vec3> stops{pb.uav.start};
  stops.insert(stops.end(), pb.via.begin(), pb.via.end());
  stops.push_back(pb.goal);
  const SegmentRule rule(world, pb.uav);
  for (std::size_t s = 0; s < stops.size(); ++s)
    if (!rule.point_ok(stops[s])) {
      res.message = stop_name(s, stops.size()) + " is closer to an obstacle than the UAV radius, or above the ceiling";
      return res;
    }
  DirectionalSearch search;
  res.route.waypoints = {pb.uav.start};
  for (std::size_t leg = 0; leg + 1 < stops.size(); ++leg) {
    Problem part = pb;
    part.uav.start = stops[leg];
    part.goal = stops[leg + 1];
    DirectionalQuery q = query_for(part, world);
    if (leg > 0) q.start_direction = res.route.waypoints.back() - res.route.waypoints[res.route.waypoints.size() - 2];
    if (leg == 0) require_lattice(world, q, 1, stop);
    const DirectionalRoute r = search.run(world, q, stop);
    res.stats.nodes_expanded += r.expanded;
    res.stats.open_max = std::max(res.stats.open_max, r.open_max);
    res.stats.cell_m = q.cell_m;
    if (!r.solved()) {
      res.fail(r.reason, r.reason == Reason::stopped ? r.message : leg_name(leg, stops.size()) + ": " + r.message);
      res.route.waypoints.clear();
      return res;
    }
    res.route.waypoints.insert(res.route.waypoints.end(), r.waypoints.begin() + 1, r.waypoints.end());
  }
  res.status = Status::solved;
  return res;
}

}  // namespace uavplan
