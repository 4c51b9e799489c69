#include "uavplan/planning/search/astar_planner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"
#include "uavplan/planning/grid_budget.h"
#include "uavplan/planning/search/grid_astar.h"
#include "uavplan/planning/search/jps2d.h"
#include "uavplan/planning/search/jps3d.h"
#include "uavplan/planning/segment_rule.h"
#include "uavplan/planning/smoothing/shortcut.h"
#include "uavplan/planning/smoothing/turn_limits.h"
#include "uavplan/planning/walled_off.h"

namespace uavplan {

AStarOptions AStarOptions::from_params(const Params& params) {
  ParamReader r(params, "astar");
  AStarOptions o = read(r);
  r.finish();
  return o;
}

AStarOptions AStarOptions::read(ParamReader& r) {
  AStarOptions o;
  o.cell_m = r.number("cell_m", o.cell_m, 0.0, 1e9, "horizontal cell size, m; 0: derived from the world's size");
  o.shortcut = r.boolean("shortcut", o.shortcut, "remove redundant waypoints along clear straight lines afterwards");
  o.refinements =
      r.integer("refinements", o.refinements, 0, 8, "with a derived cell: times it is halved when no route is found");
  o.max_cells = r.count("max_cells", o.max_cells, 1, 1'000'000'000, "a refined grid never has more cells than this");
  o.target_cells =
      r.count("target_cells", o.target_cells, 1, 1'000'000'000, "a derived cell aims at about this many voxels");
  o.jump_points = r.boolean("jump_points", o.jump_points,
                            "jump point search where cells are cubes (no climb limit) or squares (2-D): the same "
                            "lengths as A*, fewer nodes; false: A* always");
  return o;
}

double auto_cell_m(const World& world, double radius_m, std::int64_t target_cells) {
  const Vec3 ext = world.bounds().extent();
  if (ext.maxCoeff() <= 0.0) return 1.0;
  double cell = cell_for_count_m(ext, static_cast<double>(target_cells));
  if (const TerrainGrid* t = world.terrain()) cell = std::min(cell, t->cell_m());
  // Resolving much finer than the UAV's body buys nothing and costs memory.
  return std::max(cell, 0.5 * radius_m);
}

double layer_height_m(double cell_m, double max_climb_rad) {
  // 0.999: a diagonal climb then sits just inside the limit, not on it.
  return max_climb_rad >= kPi / 4 ? cell_m : cell_m * std::tan(max_climb_rad) * 0.999;
}

GridEngine grid_engine(const VoxelGrid& grid, double max_climb_rad, bool jump_points) {
  // The jump searches index cells by 32 bits.
  if (!jump_points || grid.size() >= std::int64_t{0xFFFFFFFF}) return GridEngine::astar;
  const Vec3& c = grid.cell();
  const auto same = [](double a, double b) { return std::abs(a - b) <= kRelativeTie * std::max(a, b); };
  if (!same(c.x(), c.y())) return GridEngine::astar;
  if (grid.nz() == 1) return GridEngine::jps2d;
  // Every vertical move, and cells the JPS's unit costs scale: 1, sqrt 2, sqrt 3.
  const bool all_moves = max_climb_rad >= kPi / 2 - kUnlimitedAngleSlack_rad;
  return all_moves && same(c.x(), c.z()) ? GridEngine::jps3d : GridEngine::astar;
}

namespace {

// One grid's search, by its engine: the cells of a route from one free cell to another.
class GridRouter {
 public:
  // `key` names the grid in the world's memo, where its lines are kept beside it.
  GridRouter(const World& world, const std::string& key, const VoxelGrid& grid, const UavSpec& uav, bool jump_points)
      : engine_(grid_engine(grid, uav.max_climb_rad, jump_points)) {
    const Vec3& cs = grid.cell();
    if (engine_ == GridEngine::jps3d)
      jps3d_.emplace(grid.cells(),
                     world.memo().get<Jps3dLines>(key + " lines", [&] { return jps3d_lines(grid.cells()); }));
    else if (engine_ == GridEngine::jps2d)
      jps2d_.emplace(grid.cells());
    else
      astar_.emplace(grid.cells(), bounding_box_moves(grid.cells(), cs.x(), cs.y(), cs.z(), uav.max_climb_rad),
                     GridHeuristic::euclidean, cs.x(), cs.y(), cs.z());
  }
  // Every cell of the route (a JPS's jump points filled in).
  GridSearchResult search(std::int64_t from, std::int64_t to, const StopCondition& stop) {
    if (astar_) return astar_->search(from, to, stop);
    GridSearchResult r = jps3d_ ? jps3d_->search(from, to, stop) : jps2d_->search(from, to, stop);
    if (r.solved()) r.cells = jps3d_ ? jps3d_->expand_path(r.cells) : jps2d_->expand_path(r.cells);
    return r;
  }

 private:
  GridEngine engine_;
  std::optional<GridAStar> astar_;
  std::optional<Jps3d> jps3d_;
  std::optional<Jps2d> jps2d_;
};

// The nearest free cell whose centre the UAV can fly to straight from p (and back).
std::int64_t attach(const VoxelGrid& g, const Vec3& p, const SegmentRule& rule) {
  int ci, cj, ck;
  g.cell_of(p, ci, cj, ck);
  for (int reach = 1; reach <= 4; reach *= 2) {
    const int rz =
        g.cell().z() > 0 ? std::max(reach, static_cast<int>(std::ceil(reach * g.cell().x() / g.cell().z()))) : 0;
    std::int64_t best = -1;
    double best_d = World::kInf;
    for (int k = ck - rz; k <= ck + rz; ++k)
      for (int j = cj - reach; j <= cj + reach; ++j)
        for (int i = ci - reach; i <= ci + reach; ++i) {
          if (!g.inside(i, j, k) || g.blocked(i, j, k)) continue;
          const Vec3 c = g.center(i, j, k);
          const double d = (c - p).norm();
          if (d < best_d && rule(p, c) && rule(c, p)) {
            best_d = d;
            best = g.index(i, j, k);
          }
        }
    if (best >= 0) return best;
  }
  return -1;
}

std::string fmt_m(double x) { return num_text(x) + " m"; }

// How one attempt on a grid ended (walled_off: no finer grid can find a route either).
enum class Attempt { found, no_route, walled_off, stopped };

// The proof that a leg's ends are walled apart: on a grid of up to this many cells (two bits
// each, and a 4-byte queue entry per cell reached).
constexpr std::int64_t kWallProofCells = 8'000'000;
constexpr double kWallProofBytesPerCell = 4.25;

// "... wall its start off from its goal (wall, tower and 3 more)": the obstacles that bound the
// start's region, which is the outside where the goal is the one caged.
std::string walls_text(const WalledOff& w) {
  constexpr std::size_t kNamed = 3;
  std::string out =
      "no way joins its ends at any cell size: the obstacles, inflated by the UAV's radius and clearance, "
      "wall its start off from its goal";
  for (std::size_t i = 0; i < w.walls.size() && i < kNamed; ++i) out += (i ? ", " : " (") + w.walls[i];
  if (w.walls.size() > kNamed) out += " and " + std::to_string(w.walls.size() - kNamed) + " more";
  if (!w.walls.empty()) out += ")";
  return out;
}

// Whether the leg from a to b is walled off, where a grid that small fits.
bool prove_walled_off(const World& world, const SegmentRule& rule, const Vec3& a, const Vec3& b,
                      const StopCondition& stop, std::string& why) {
  if (!grid_fits(static_cast<double>(kWallProofCells), kWallProofBytesPerCell, stop)) return false;
  const WalledOff w = walled_off(world, rule.inflation_m(), rule.ceiling_m(), a, b, kWallProofCells, stop);
  if (w.apart) why = walls_text(w);
  return w.apart;
}

// The route through every stop on one grid, each leg straight where it is clear, else grid A*
// between the free cells reached straight from its ends; `pinned` marks the stops.
// On the first grid, a leg without a route is checked for walls before finer grids are tried.
// The grid key of a cell size and a body's rule on a world (every input of the voxelisation).
std::string grid_key(const Vec3& cell3, const SegmentRule& rule) {
  return strf("astar lattice %.17g %.17g %.17g %.17g %.17g", cell3.x(), cell3.y(), cell3.z(), rule.inflation_m(),
              rule.ceiling_m());
}

Attempt route_on_grid(const World& world, const std::string& key, const VoxelGrid& grid, const UavSpec& uav,
                      const SegmentRule& rule, const std::vector<Vec3>& stops, bool derived, bool first,
                      bool jump_points, const StopCondition& stop, PlanResult& res, std::vector<Vec3>& path,
                      std::vector<char>& pinned) {
  const Vec3& cs = grid.cell();
  GridRouter search(world, key, grid, uav, jump_points);
  path.assign(1, stops[0]);
  pinned.assign(1, 1);
  for (std::size_t s = 0; s + 1 < stops.size(); ++s) {
    const Vec3 &a = stops[s], &b = stops[s + 1];
    if (rule(a, b)) {
      path.push_back(b);
      pinned.push_back(1);
      continue;
    }
    const std::int64_t ga = attach(grid, a, rule), gb = attach(grid, b, rule);
    if (ga < 0 || gb < 0) {
      res.reason = Reason::no_route;
      res.message = leg_name(s, stops.size()) + ": no free cell of the " + fmt_m(cs.x()) +
                    " grid can be reached straight from its " + (ga < 0 ? "start" : "end") +
                    "; a smaller planner.params.cell_m gives cells in narrower room";
      return Attempt::no_route;
    }
    const GridSearchResult vp = search.search(ga, gb, stop);
    res.stats.nodes_expanded += vp.expanded;
    res.stats.open_max = std::max(res.stats.open_max, vp.open_max);
    if (vp.reason == Reason::stopped) {
      res.message = "stopped before a route was found";
      res.reason = Reason::stopped;
      return Attempt::stopped;
    }
    if (!vp.solved()) {
      res.reason = Reason::no_route;
      std::string walls;
      if (first && prove_walled_off(world, rule, a, b, stop, walls)) {
        res.message = leg_name(s, stops.size()) + ": " + walls;
        return Attempt::walled_off;
      }
      res.message = leg_name(s, stops.size()) + ": no route on a " + std::to_string(grid.nx()) + "x" +
                    std::to_string(grid.ny()) + "x" + std::to_string(grid.nz()) + " grid of " + fmt_m(cs.x()) +
                    " cells; a smaller planner.params.cell_m finds narrower gaps" +
                    (derived ? " (the derived cell was halved while the grid stayed under planner.params.max_cells "
                               "and --max-memory)"
                             : "");
      return Attempt::no_route;
    }
    for (const std::int64_t c : vp.cells) {
      path.push_back(grid.center(c));
      pinned.push_back(0);
    }
    path.push_back(b);
    pinned.push_back(1);
  }
  return Attempt::found;
}

// The stops' places in a path (in order): pins survive shortcutting by construction.
std::vector<char> stop_pins(const std::vector<Vec3>& path, const std::vector<Vec3>& stops) {
  std::vector<char> pins(path.size(), 0);
  std::size_t s = 0;
  for (std::size_t i = 0; i < path.size() && s < stops.size(); ++i)
    if ((path[i] - stops[s]).norm() == 0.0) {
      pins[i] = 1;
      ++s;
    }
  return pins;
}

}  // namespace

PlanResult AStarPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult res;
  const UavSpec& uav = pb.uav;
  const SegmentRule rule(world, uav);
  std::vector<Vec3> stops{uav.start};
  stops.insert(stops.end(), pb.via.begin(), pb.via.end());
  stops.push_back(pb.goal);
  for (std::size_t s = 0; s < stops.size(); ++s)
    if (!rule.point_ok(stops[s])) {
      res.message = stop_name(s, stops.size()) + " is closer to an obstacle than the UAV radius, or above the ceiling";
      return res;
    }
  // A derived cell is halved while no route is found and the grid fits.
  const bool derived = options_.cell_m <= 0.0;
  double cell = derived ? auto_cell_m(world, uav.radius_m, options_.target_cells) : options_.cell_m;
  const int attempts = derived ? options_.refinements + 1 : 1;
  std::vector<Vec3> path;
  std::vector<char> pinned;
  Attempt attempt = Attempt::no_route;
  for (int k = 0; k < attempts && attempt == Attempt::no_route; ++k, cell *= 0.5) {
    const Vec3 cell3(cell, cell, layer_height_m(cell, uav.max_climb_rad));
    const double cells = VoxelGrid::cell_count(world.bounds(), cell3);
    // A bit per voxel and a search node (16 bytes) per voxel reached.
    constexpr double kBytesPerVoxel = 16.125;
    if (k > 0 && (cells > static_cast<double>(options_.max_cells) || !grid_fits(cells, kBytesPerVoxel, stop))) break;
    require_grid(cells, kBytesPerVoxel, stop,
                 derived ? "the derived cell of " + fmt_m(cell) : "planner.params.cell_m = " + fmt_m(cell));
    // Made once per world, cell and body: the UAVs of a mission and the plans of a batch share it.
    const std::string key = grid_key(cell3, rule);
    const std::shared_ptr<const VoxelGrid> grid = world.memo().get<VoxelGrid>(
        key, [&] { return voxelize(world, cell3, rule.inflation_m(), rule.ceiling_m(), stop, CellRule::lattice); });
    res.stats.grid_cells = static_cast<std::uint64_t>(grid->size());
    res.stats.cell_m = grid->cell().x();
    attempt = route_on_grid(world, key, *grid, uav, rule, stops, derived, k == 0, options_.jump_points, stop, res, path,
                            pinned);
  }
  if (attempt != Attempt::found) return res;
  for (std::size_t i = 1; i < path.size(); ++i) res.stats.grid_route_m += (path[i] - path[i - 1]).norm();
  if (options_.shortcut) {
    path = shortcut(path, pinned, rule);
    pinned = stop_pins(path, stops);
  }
  const TurnShaping shaped =
      enforce_turn_limits(path, pinned, uav.heading_rad, {uav.max_turn_rad, uav.max_climb_rad}, rule);
  if (!shaped.solved()) {
    res.fail(shaped.reason, shaped.message);
    return res;
  }
  res.route.waypoints = shaped.waypoints;
  res.status = Status::solved;
  return res;
}

}  // namespace uavplan
