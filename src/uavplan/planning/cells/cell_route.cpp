#include "uavplan/planning/cells/cell_route.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "uavplan/planning/segment_rule.h"
#include "uavplan/planning/smoothing/turn_limits.h"

namespace uavplan {

void CellPlanOptions::read(ParamReader& r) {
  cell_m = r.number("cell_m", cell_m, 0.0, 1e6, "the cell map's cell, m; 0: the terrain's cell, else the bounds / 64");
  level_m = r.number("level_m", level_m, 0.0, 1e6, "the spacing of heights, m; 0: cell_m / 2");
  weights.w1 = r.number("w1", weights.w1, 0.0, 1e12, "w1, the range term's weight (P2 eq. 1)");
  weights.w2 = r.number("w2", weights.w2, -1.0, 1e12, "w2, the height term's weight (negative: height rewarded)");
  weights.w3 = r.number("w3", weights.w3, 0.0, 1e12, "w3, the threat term's weight");
}

namespace {

double ceiling_of(const Problem& p, const World& w) {
  return p.uav.ceiling_m ? std::min(*p.uav.ceiling_m, w.bounds().max.z()) : w.bounds().max.z();
}

CellMap make_map(const Problem& p, const World& w, const CellPlanOptions& o, const StopCondition& stop) {
  CellMapOptions mo;
  mo.cell_m = o.cell_m;
  mo.level_m = o.level_m;
  mo.inflation_m = p.uav.radius_m + kPlanningMargin_m;
  mo.ceiling_m = ceiling_of(p, w);
  return CellMap(w, mo, stop);
}

// A free node near p (its column and the eight around, levels near p's height) that p reaches
// in a straight, checked segment (the climb limit included), nearest first; -1 when none.
std::int64_t attach(const CellMap& map, const Vec3& p, const SegmentRule& rule) {
  int ci = 0, cj = 0;
  map.cell_of(p, ci, cj);
  std::vector<std::pair<double, std::int64_t>> cand;
  for (int j = std::max(0, cj - 1); j <= std::min(map.ny() - 1, cj + 1); ++j)
    for (int i = std::max(0, ci - 1); i <= std::min(map.nx() - 1, ci + 1); ++i)
      for (int k = 0; k < map.levels(); ++k)
        if (map.free(i, j, k) && map.level_z(k) <= rule.ceiling_m())
          cand.emplace_back((map.centre(i, j, k) - p).norm(), map.index(i, j, k));
  std::sort(cand.begin(), cand.end());
  for (const auto& [d, n] : cand)
    if (d < kSamePoint_m || rule(p, map.centre(n))) return n;
  return -1;
}

// What to change when the cell map has no route. A move climbs at least one level over one
// diagonal cell: a map whose least climb is steeper than the climb limit cannot change height.
// Obstacles with room for a body under them, the widest named: the cell map counts their columns
// blocked down to the ground.
std::string overhang_hint(const World& world, double inflation_m) {
  std::size_t count = 0, widest = 0;
  double widest_m2 = -1.0, widest_under_m = 0.0;
  for (std::size_t k = 0; k < world.obstacles().size(); ++k) {
    const Aabb box = bounding_box(world.obstacles()[k]);
    const Vec3 c = box.center(), e = box.extent();
    const double under = box.min.z() - world.ground_z(c.x(), c.y());
    if (under <= 2 * inflation_m) continue;
    ++count;
    if (e.x() * e.y() > widest_m2) {
      widest_m2 = e.x() * e.y();
      widest = k;
      widest_under_m = under;
    }
  }
  if (count == 0) return {};
  return "the cell map models columns, and " + world.obstacle_label(widest) +
         (count > 1 ? " (and " + std::to_string(count - 1) + " more)" : std::string()) + " is " +
         num_text(widest_under_m) +
         " m above the ground: the space under it counts as blocked (astar, rrt and directional_astar plan under it)";
}

std::string cells_hint(const CellMap& map, double max_climb_rad, const World& world, double inflation_m) {
  if (std::string overhang = overhang_hint(world, inflation_m); !overhang.empty()) return overhang;
  const double least_climb = std::atan2(map.level_m(), std::sqrt(2.0) * map.cell_m());
  if (map.levels() > 1 && least_climb > max_climb_rad + 1e-12) {
    const double most = std::sqrt(2.0) * map.cell_m() * std::tan(max_climb_rad);
    const double unit = std::pow(10.0, std::floor(std::log10(most)) - 2);  // three digits, rounded down
    return strf(
        "the cell map's least climb (one level of %g m over a diagonal cell of %g m) is %.1f deg, steeper than the "
        "climb limit of %.1f deg, so it cannot change height: give planner.params.level_m <= %g",
        map.level_m(), map.cell_m(), rad_to_deg(least_climb), rad_to_deg(max_climb_rad),
        std::floor(most / unit) * unit);
  }
  return strf("a smaller planner.params.cell_m (now %g m) finds narrower streets", map.cell_m());
}

}  // namespace

CellWorld::CellWorld(const Problem& p, const World& w, const CellPlanOptions& o, const StopCondition& stop)
    : map(make_map(p, w, o, stop)),
      graph(map, w, p.uav.speed.cruise_mps, o.weights, p.uav.max_climb_rad, ceiling_of(p, w)) {}

double cell_route_cost(const CellGraph& g, const std::vector<Vec3>& wp) {
  double j = 0.0;
  for (std::size_t i = 1; i < wp.size(); ++i) j += g.cost(wp[i - 1], wp[i]);
  return j;
}

namespace {

// A via point is reached from its attach cell and left through the same cell: an out-and-back
// spike (a 180 degree turn). Cut one side of it where the straight segment is safe.
void cut_spikes(std::vector<Vec3>& route, std::vector<char>& pinned, const SegmentRule& rule) {
  for (std::size_t i = 1; i + 1 < route.size(); ++i) {
    if (!pinned[i] || (route[i - 1] - route[i + 1]).norm() > kSamePoint_m) continue;
    if (i + 2 < route.size() && rule(route[i], route[i + 2])) {
      route.erase(route.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      pinned.erase(pinned.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    } else if (i >= 2 && rule(route[i - 2], route[i])) {
      route.erase(route.begin() + static_cast<std::ptrdiff_t>(i) - 1);
      pinned.erase(pinned.begin() + static_cast<std::ptrdiff_t>(i) - 1);
    }
  }
}

// Collinear runs become one segment (the same cost: every term is additive along a line).
void merge_collinear(const std::vector<Vec3>& route, const std::vector<char>& pinned, std::vector<Vec3>& wp,
                     std::vector<char>& pins) {
  wp.assign(1, route[0]);
  pins.assign(1, pinned[0]);
  for (std::size_t i = 1; i < route.size(); ++i) {
    if (i + 1 < route.size() && !pinned[i]) {
      const Vec3 a = (route[i] - wp.back()).normalized(), b = (route[i + 1] - route[i]).normalized();
      if (a.dot(b) > 1.0 - 1e-12) continue;
    }
    wp.push_back(route[i]);
    pins.push_back(pinned[i]);
  }
}

// The cell map is conservative; every segment is still checked exactly. Empty, or why not.
std::string exact_check(const std::vector<Vec3>& wp, const SegmentRule& rule) {
  const auto f = [](const Vec3& v) {
    const std::string b = strf("(%.2f, %.2f, %.2f)", v.x(), v.y(), v.z());
    return std::string(b);
  };
  for (std::size_t i = 1; i < wp.size(); ++i)
    if (!rule(wp[i - 1], wp[i]))
      return "internal: the cell move " + f(wp[i - 1]) + " -> " + f(wp[i]) + " failed the exact segment check";
  return {};
}

// Each leg's cells between the stops' attach nodes: the route through their centres, the stops
// pinned. False with res's message and reason where a leg has none (`finer_may_help` when finer
// cells could find one) or the stop came first.
bool route_legs(const World& world, const CellWorld& cw, const std::vector<Vec3>& stops,
                const std::vector<std::int64_t>& nodes, const Problem& problem, const StopCondition& stop,
                const CellLegSearch& search, PlanResult& res, std::vector<Vec3>& route, std::vector<char>& pinned,
                bool& finer_may_help) {
  route.assign(1, stops[0]);
  pinned.assign(1, 1);
  for (std::size_t leg = 0; leg + 1 < stops.size(); ++leg) {
    const bool stopped_before = stop.should_stop();
    // Under a time limit each leg may spend its share of what is left, so that an anytime
    // search (the colony) leaves time for the legs after it.
    const double legs_left = static_cast<double>(stops.size() - leg);  // and what follows them
    const StopCondition leg_stop =
        stop.has_time_limit() ? stop | StopCondition::time_limit(stop.seconds_left() / legs_left) : stop;
    const auto path = stopped_before
                          ? std::nullopt
                          : search(cw.graph, nodes[leg], nodes[leg + 1], static_cast<int>(leg), res.stats, leg_stop);
    if (!path && (stopped_before || stop.should_stop())) {  // the search was cut short: no advice on the cells
      res.message = "stopped before the route was complete";
      res.reason = Reason::stopped;
      return false;
    }
    if (!path) {
      res.reason = Reason::no_route;
      res.message = leg_name(leg, stops.size()) + ": no route on the cell map; " +
                    cells_hint(cw.map, problem.uav.max_climb_rad, world, problem.uav.radius_m);
      finer_may_help = true;
      return false;
    }
    for (std::int64_t n : *path) {
      const Vec3 c = cw.map.centre(n);
      if ((c - route.back()).norm() > kSamePoint_m) {
        route.push_back(c);
        pinned.push_back(0);
      }
    }
    if ((stops[leg + 1] - route.back()).norm() > kSamePoint_m) {
      route.push_back(stops[leg + 1]);
      pinned.push_back(1);
    } else {
      pinned.back() = 1;
    }
  }
  return true;
}

// One attempt at the options' cell size. `finer_may_help` is set when it failed because the
// cells are too coarse for the streets: a stop cannot attach, or a leg has no route.
PlanResult plan_once(const Problem& problem, const World& world, const CellPlanOptions& options,
                     const StopCondition& stop, const CellLegSearch& search, bool& finer_may_help) {
  finer_may_help = false;
  PlanResult res;
  const CellWorld cw(problem, world, options, stop);
  const CellMap& map = cw.map;
  const SegmentRule rule(world, problem.uav);
  res.stats.grid_cells = static_cast<std::uint64_t>(map.nodes());
  res.stats.cell_m = map.cell_m();
  std::vector<Vec3> stops{problem.uav.start};
  stops.insert(stops.end(), problem.via.begin(), problem.via.end());
  stops.push_back(problem.goal);
  std::vector<std::int64_t> nodes;
  for (std::size_t s = 0; s < stops.size(); ++s) {
    nodes.push_back(attach(map, stops[s], rule));
    if (nodes.back() < 0) {
      res.message = stop_name(s, stops.size()) +
                    " cannot reach a free cell of the cell map straight within its limits; " +
                    cells_hint(map, problem.uav.max_climb_rad, world, problem.uav.radius_m);
      finer_may_help = true;
      return res;
    }
  }
  std::vector<Vec3> route, wp;
  std::vector<char> pinned, pins;
  if (!route_legs(world, cw, stops, nodes, problem, stop, search, res, route, pinned, finer_may_help)) return res;
  cut_spikes(route, pinned, rule);
  merge_collinear(route, pinned, wp, pins);
  res.message = exact_check(wp, rule);
  if (!res.message.empty()) return res;
  // P2 treats the UAV as a point mass; a UAV with a turn limit or start heading gets its
  // corners shaped (fillets, every new segment checked).
  finish_with_turns(wp, pins, problem.uav, rule, res);
  return res;
}

}  // namespace

PlanResult plan_on_cells(const Problem& problem, const World& world, const CellPlanOptions& options,
                         const StopCondition& stop, const CellLegSearch& search) {
  // The default cell (bounds / 64, or the terrain's) can be wider than a city's streets. When it
  // is too coarse and the size was not chosen, halve it (levels follow unless chosen too) while
  // the map stays within kMaxRefinedNodes; an explicit cell_m is taken as it is.
  constexpr std::uint64_t kMaxRefinedNodes = 4'000'000;
  CellPlanOptions o = options;
  bool finer_may_help = false;
  PlanResult res = plan_once(problem, world, o, stop, search, finer_may_help);
  while (res.status != Status::solved && finer_may_help && options.cell_m <= 0.0 && !stop.should_stop() &&
         res.stats.grid_cells > 0 && res.stats.grid_cells * 8 <= kMaxRefinedNodes) {
    o.cell_m = res.stats.cell_m / 2.0;
    if (options.level_m <= 0.0) o.level_m = o.cell_m / 2.0;
    res = plan_once(problem, world, o, stop, search, finer_may_help);
  }
  return res;
}

}  // namespace uavplan
