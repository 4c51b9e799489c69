#include "uavplan/planning/field/field_guide.h"

#include <algorithm>
#include <cmath>

#include "uavplan/planning/search/astar_planner.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

namespace {

Vec3 guide_cell(const World& world, const UavSpec& uav, double cell_m, std::int64_t max_cells) {
  const Vec3 ext = world.bounds().extent();
  for (;; cell_m *= 1.25) {
    const Vec3 cell(cell_m, cell_m, layer_height_m(cell_m, uav.max_climb_rad));
    if (VoxelGrid::cell_count(world.bounds(), cell) <= static_cast<double>(max_cells) || cell_m > ext.norm())
      return cell;
  }
}

// Square cells in a flat grid, cubic ones otherwise, to within the tiling's rounding (a guide
// need not be optimal: octile on cells 0.1 % off square overestimates by as much).
bool cubic(const VoxelGrid& g) {
  const Vec3 c = g.cell();
  auto near = [](double a, double b) { return std::abs(a - b) <= 1e-3 * std::max(a, b); };
  return near(c.x(), c.y()) && (g.nz() == 1 || near(c.x(), c.z()));
}

}  // namespace

FieldGuide::Level::Level(const World& world, const UavSpec& uav, const Vec3& cell, const StopCondition& stop)
    // A cell is blocked when its centre is within the inflation of an obstacle (voxelize adds
    // the half-diagonal to be conservative; a guide wants the narrow passages too).
    : grid(voxelize(world, cell, std::max(0.0, SegmentRule(world, uav).inflation_m() - 0.5 * cell.norm()),
                    SegmentRule(world, uav).ceiling_m(), stop)),
      search(grid.cells(),
             bounding_box_moves(grid.cells(), grid.cell().x(), grid.cell().y(), grid.cell().z(), uav.max_climb_rad),
             // Octile: the exact free-space distance on square (2-D) or cubic cells, so the
             // search runs straight at the goal in the open; on layered cells the admissible
             // Euclidean distance.
             cubic(grid) ? GridHeuristic::octile : GridHeuristic::euclidean, grid.cell().x(), grid.cell().y(),
             grid.cell().z()) {}

FieldGuide::FieldGuide(const World& world, const UavSpec& uav, double cell_m, std::int64_t max_cells,
                       const StopCondition& stop)
    : world_(&world), uav_(uav), max_cells_(max_cells), stop_(stop) {
  levels_.push_back(std::make_unique<Level>(world, uav, guide_cell(world, uav, cell_m, max_cells), stop_));
}

namespace {

// The free cell nearest to p within a few cells of it, else -1.
std::int64_t attach(const VoxelGrid& grid, const Vec3& p) {
  int ci, cj, ck;
  grid.cell_of(p, ci, cj, ck);
  const bool flat = grid.nz() == 1;
  for (int reach = 0; reach <= 4; ++reach) {
    std::int64_t best = -1;
    double best_d = World::kInf;
    const int rz = flat ? 0 : reach;
    for (int k = ck - rz; k <= ck + rz; ++k)
      for (int j = cj - reach; j <= cj + reach; ++j)
        for (int i = ci - reach; i <= ci + reach; ++i) {
          if (!grid.inside(i, j, k) || grid.blocked(i, j, k)) continue;
          const double d = (grid.center(i, j, k) - p).norm();
          if (d < best_d) best_d = d, best = grid.index(i, j, k);
        }
    if (best >= 0) return best;
  }
  return -1;
}

}  // namespace

std::vector<Vec3> FieldGuide::route(const Vec3& from, const Vec3& goal, std::span<const KeepOut> keep_out) {
  std::vector<Vec3> out = route_on(*levels_.back(), from, goal, keep_out);
  while (out.empty() && static_cast<int>(levels_.size()) <= kRefinements) {
    const VoxelGrid& g = levels_.back()->grid;
    const Vec3 finer(0.5 * g.cell().x(), 0.5 * g.cell().y(), g.nz() > 1 ? 0.5 * g.cell().z() : g.cell().z());
    if (VoxelGrid::cell_count(world_->bounds(), finer) > static_cast<double>(max_cells_)) break;
    levels_.push_back(std::make_unique<Level>(*world_, uav_, finer, stop_));
    out = route_on(*levels_.back(), from, goal, keep_out);
  }
  return out;
}

std::vector<Vec3> FieldGuide::route_on(Level& level, const Vec3& from, const Vec3& goal,
                                       std::span<const KeepOut> keep_out) {
  // Keep-outs block the cells whose centre they cover; cells already blocked stay as they were.
  marked_.clear();
  VoxelGrid& g = level.grid;
  for (const KeepOut& o : keep_out) {
    int i0, j0, k0, i1, j1, k1;
    g.cell_of(o.centre - Vec3::Constant(o.radius_m), i0, j0, k0);
    g.cell_of(o.centre + Vec3::Constant(o.radius_m), i1, j1, k1);
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const std::int64_t idx = g.index(i, j, k);
          if (g.blocked(idx) || (g.center(i, j, k) - o.centre).norm() >= o.radius_m) continue;
          g.set_blocked(idx);
          marked_.push_back(idx);
        }
  }
  std::vector<Vec3> out;
  const std::int64_t a = attach(g, from), b = attach(g, goal);
  if (a >= 0 && b >= 0) {
    const GridSearchResult r = level.search.search(a, b, stop_);
    if (r.solved()) {
      for (const std::int64_t c : r.cells) out.push_back(g.center(c));
      out.push_back(goal);
    }
  }
  for (const std::int64_t idx : marked_) g.set_blocked(idx, false);
  return out;
}

}  // namespace uavplan
