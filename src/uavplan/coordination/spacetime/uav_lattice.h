// UAVs in space and time on a lattice: the world's free space as a regular 3-D lattice (26
// neighbours, edges clear of obstacles and terrain by the largest body), the UAVs' own points
// (starts, via points, goals) as extra vertices joined to the lattice round them, and one time
// step (tick) for every move and wait. Every UAV flies each move in one tick, so between ticks
// any two UAVs move linearly and their smallest distance in a step is exact in closed form:
// the conflicts are those of the piecewise-linear trajectories, the verifier's own test
// (separation centre to centre, never less than both radii).
//
// A step's conflicts depend only on the two moves, not on when they happen: what a move u -> v
// forbids another UAV in its step (vertices at the step's start, moves and waits during it) is
// found once per move and kept. A lattice move's list is its direction's pattern shifted (the
// lattice is the same everywhere); moves touching the UAVs' own points are measured one by one.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "uavplan/coordination/spacetime/space_time_graph.h"
#include "uavplan/coordination/spacetime/space_time_model.h"
#include "uavplan/core/units.h"
#include "uavplan/core/vec.h"
#include "uavplan/world/moving.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct UavLatticeOptions {
  double cell_m = 0.0;             // lattice spacing; 0: lattice_cell_m
  double body_m = 0.5;             // edges keep this far from obstacles and terrain
  double need_m = 1.0;             // two UAVs' centres closer than this conflict
  double max_climb_rad = kPi / 2;  // steeper edges are left out
  double ceiling_z = World::kInf;  // no vertex above
};

// The spacing a lattice gets by default: a little above the separation, and coarse enough that
// the world's bounds hold at most about kLatticeCells cells.
inline constexpr int kLatticeCells = 1 << 17;
double lattice_cell_m(const Aabb& bounds, double need_m);
// The cells of a lattice of spacing `cell_m` over `bounds` (place_cells' count).
std::uint64_t lattice_cell_count(const Aabb& bounds, double cell_m);

struct UavLattice {
  Vec3 origin = Vec3::Zero();  // the cell (0, 0, 0)
  double cell_m = 1.0;
  int nx = 0, ny = 0, nz = 0;
  SpaceTimeGraph graph;        // the cells first (cell (i, j, k) = (k * ny + j) * nx + i), then the points
  std::vector<Vec3> position;  // per vertex
  double longest_edge_m = 0.0;

  int cell_count() const { return nx * ny * nz; }
  bool is_cell(int v) const { return v < cell_count(); }
  // The vertex of the i-th point given to build_uav_lattice.
  int point_vertex(std::size_t i) const { return cell_count() + static_cast<int>(i); }
};

// The lattice over the world's free space with `points` as extra vertices, each joined to the
// lattice vertices (and other points) within one lattice diagonal that it sees clear. Throws
// std::invalid_argument beyond SpaceTimeTable::kMostVertices vertices (a larger cell_m helps).
UavLattice build_uav_lattice(const World& world, std::span<const Vec3> points, const UavLatticeOptions& o,
                             const StopCondition& stop);

// Agents on a lattice, each from its start through its targets in order (via points, then its
// goal, where it stays for ever once there). A multi-target path is its legs one after another,
// each the best from where and when the one before ended (not the best over all of them).
struct LatticeAgent {
  int start = 0;
  std::vector<int> targets;     // at least one: the goal last
  double max_turn_rad = kPi;    // between consecutive moves
  Vec3 heading = Vec3::Zero();  // at the start (zero: any)
};

// Targets x vertices up to which the searches get exact distances to their targets (one sweep of
// the graph each); beyond, a bound in closed form (the lattice's Chebyshev distance).
inline constexpr std::uint64_t kExactTableEntries = std::uint64_t{1} << 23;
// Moving obstacles are followed this many ticks at most, and kept this much farther.
inline constexpr int kMostMovingTicks = 1 << 14;
inline constexpr double kMovingMargin_m = 1e-3;

class LatticeAgents final : public SpaceTimeModel {
 public:
  // `need_m`: centres closer than this conflict. Throws std::invalid_argument when the agents'
  // distance tables (one per distinct target, made on `threads` threads) would pass
  // kMostDistanceTableBytes.
  LatticeAgents(const UavLattice& lattice, std::vector<LatticeAgent> agents, double need_m, int threads = 1);

  int agent_count() const override { return static_cast<int>(agents_.size()); }
  int vertex_count() const override { return lattice_.graph.vertex_count; }
  SpaceTimeAnswer plan(int agent, const SpaceTimeTable& forbidden, const SpaceTimeTable* avoided, double w,
                       SpaceTimeSearches& search, const StopCondition& stop) const override;
  int lone_cost(int agent) const override { return lone_[agent]; }
  void add_path(int agent, const SpaceTimePath& path, SpaceTimeTable& table) const override;
  std::optional<PathConflict> first_conflict(const std::vector<SpaceTimePath>& paths) const override;
  int count_conflicts(const std::vector<SpaceTimePath>& paths) const override;

  // Whether an agent can reach each of its targets in turn (ignoring the others).
  bool reachable(int agent) const { return lone_[agent] >= 0; }

  // Moving obstacles known in advance, kept `keep_m` from their surfaces (and kMovingMargin_m
  // more), the lattice's tick k being t0_s + k tick_s: forbidden to every agent, followed until
  // they stop (then for ever), leave the lattice for good, or kMostMovingTicks.
  void keep_off_moving(const std::vector<MovingObstacle>& obstacles, double keep_m, double t0_s, double tick_s);
  // Their entries (null without moving obstacles).
  const SpaceTimeTable* moving() const { return has_moving_ ? &moving_ : nullptr; }

 private:
  // What the move u -> v (u == v: a wait at u) forbids another agent in its step: being at a
  // vertex at the step's start, and moves (waits too) during it.
  struct Entries {
    std::vector<int> vertices;
    std::vector<std::pair<int, int>> moves;
  };
  const Entries& entries_of(int u, int v) const;
  Vec3 arrival_direction(const SpaceTimePath& path, const Vec3& start) const;
  void measure(int u, int v, Entries& out) const;
  void shift_pattern(int u, int v, Entries& out) const;
  void add_near_points(int u, int v, Entries& out) const;
  void measure_near(const Vec3& a0, const Vec3& a1, double need_m, bool cells, bool ends_next, Entries& out) const;
  Aabb lattice_bounds() const;
  bool moves_conflict(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) const;
  // Every conflict among the paths, by time, each as found; stops at the first when `first`.
  int scan(const std::vector<SpaceTimePath>& paths, bool first, PathConflict* out) const;

  const UavLattice& lattice_;
  std::vector<LatticeAgent> agents_;
  double need_m_;
  double reach_m_;                                       // need_m_ + the longest edge
  std::unordered_map<int, std::vector<int>> to_target_;  // distances to each target vertex
  std::vector<int> lone_;
  mutable std::unordered_map<std::uint64_t, Entries> entries_;
  struct Pattern {
    bool made = false;
    std::vector<Eigen::Vector3i> vertices;
    std::vector<std::pair<Eigen::Vector3i, int>> moves;  // (offset of the other's start, its direction)
  };
  mutable std::vector<Pattern> patterns_;  // per direction (27: index 13 is the wait)
  SpaceTimeTable moving_;                  // the moving obstacles' entries
  bool has_moving_ = false;
};

}  // namespace uavplan
