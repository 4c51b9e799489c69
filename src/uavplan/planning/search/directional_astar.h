// Directional A* (P4, Chen et al. 2019): the search state carries a heading, and a node
// expands only the cone the UAV can fly: yaw offsets spread over [-psi_max, psi_max] around its
// heading and pitch over [-phi_max, phi_max], M directions each, at step L cells, each end
// snapped to the nearest lattice point ("nearest equivalent", P4 sec. 2.2). f = g + Euclidean h
// (P4 eq. 5-6). A node with no feasible child is a dead zone: it is closed and the next best
// open node is taken, in a loop, until a route is found (P4 sec. 2.3, eq. 7). P4 closes a lattice
// point once, which leaves no route where a point was first reached facing a wall; by default a
// state is a lattice point with the heading sector (8 of them) it was reached in, so such a point
// can be passed again facing along the wall (the rendezvous's re-planning keeps P4's one state).
// Every segment is checked exactly: inside the bounds, clear of obstacles after inflation,
// pitch within phi_max, turn (3-D angle and yaw change) within psi_max, the first one against
// the start heading. Eq. 8 of the paper swaps psi and phi; we use
// x += L cos(phi) cos(psi), y += L cos(phi) sin(psi), z += L sin(phi).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "uavplan/core/status.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"
#include "uavplan/planning/search/best_first.h"
#include "uavplan/world/shapes.h"

namespace uavplan {

struct DirectionalAStarOptions {
  double cell_m = 0.0;         // lattice spacing; 0 = derived from the world (see below)
  double step_cells = 0.0;     // L; 0 = max(2.5, 2 / psi_max, in 3-D 1 / tan(phi_max)): lattice
                               // directions L cells away are about 1/L rad apart, so a finer turn
                               // limit needs a longer step; a move climbs at least one cell in L
  int directions = 3;          // M, for yaw and (in 3-D) for pitch
  double max_yaw_rad = 0.0;    // psi_max; 0 = the UAV's max_turn (60 deg if it has none)
  double max_pitch_rad = 0.0;  // phi_max; 0 = the UAV's max_climb (30 deg if it has none)
  std::int64_t max_expansions = 2'000'000;
  std::int64_t target_points = 100'000;  // a derived lattice has about this many points
  // Used by the rendezvous (P4 sec. 3): the largest L of the multi-step search, and the minimum
  // turn radius R_min of the loiter circle (0 = one lattice cell).
  double step_cells_max = 3.0;
  double min_turn_radius_m = 0.0;
  double heuristic_weight = 1.0;  // f = g + w h; w > 1 trades length for speed
  // h = max(Euclidean, |dz| / sin(phi_max)): still a lower bound (and consistent), so the same
  // route lengths with far fewer expansions where the climb limit binds (a spiral up; half the
  // open nodes on P4's Table 3). false: P4's own h, the Euclidean distance (eq. 6).
  bool climb_bound = true;
  // h raised to the exact length left in the relaxed problem: the same lattice, obstacles and
  // moves (those of every cone the search can reach), no turn limit between moves; computed from
  // the goal as the search asks (Reverse Resumable A*, Silver 2005). A lower bound and consistent,
  // so the same route lengths; it closes the gap that makes a Euclidean h open every state within
  // the route's excess length (an ellipsoid), and prunes points that cannot reach the goal at all.
  // Off by default: its reverse search closes more points than it spares the search (P4's Table 3:
  // 5,700 against 700-1,500 expansions spared, twice the time).
  bool relaxed_heuristic = false;
  // w of a first search with f = g + w h whose route bounds the exact one (DirectionalQuery::
  // incumbent_weight); 1 = none.
  double incumbent_weight = 1.2;

  static DirectionalAStarOptions from_params(const Params& params);

  // The declaration of its parameters: reads them from r (params.h).

  static DirectionalAStarOptions read(ParamReader& r);
};

// solved, or failed for stopped, budget (max_expansions), no_route or invalid (the query).
struct DirectionalRoute : Outcome {
  std::vector<Vec3> waypoints;
  double length_m = 0.0;
  std::uint64_t expanded = 0, generated = 0, dead_zones = 0;
  std::uint64_t opened = 0;            // distinct states ever on the open list, the start included
  std::uint64_t cells_opened = 0;      // distinct lattice points among them (P4's "OPEN grid cells")
  std::uint64_t open_max = 0;          // the most entries the open list held at once
  std::uint64_t relaxed_expanded = 0;  // points the relaxed heuristic's reverse search closed
};

// One directional search from `start` (with optional heading) to `goal`; `virtual_threats`
// are extra spheres to avoid (P4's virtual threats). Resolved limits and cell must be given.
struct DirectionalQuery {
  Vec3 start, goal;
  std::optional<double> heading_rad;
  // The start's heading in 3-D where it has one (the last segment of the leg before a via
  // point); it wins over heading_rad.
  std::optional<Vec3> start_direction;
  double cell_m;
  double step_cells;
  int directions;
  double max_yaw_rad, max_pitch_rad;
  double inflation_m;
  double ceiling_m;
  std::int64_t max_expansions = 2'000'000;
  std::vector<Sphere> virtual_threats;
  // A state is a lattice point and the heading sector (of 8) it was reached in, so a point
  // closed facing a wall can still be passed facing along it; false: P4's one state per point.
  bool heading_states = true;
  double heuristic_weight = 1.0;
  bool climb_bound = false;        // see DirectionalAStarOptions
  bool relaxed_heuristic = false;  // see DirectionalAStarOptions
  // Give up once every open route is longer than this (f = g + h is a lower bound on the
  // length through a node when heuristic_weight is 1): the rendezvous' multi-step search
  // need not finish a route that cannot beat its best.
  double max_length_m = std::numeric_limits<double>::infinity();
  // Where the search is exact (heuristic_weight 1, no length bound): a first search with
  // f = g + w h (w = incumbent_weight > 1) finds a route in few expansions, and its length bounds
  // the exact search, which then never puts on the list a node that cannot beat it (f above the
  // bound). The route is the exact search's (or the first's where none is shorter): the same
  // lengths, a fraction of the open nodes. 1: the exact search alone.
  double incumbent_weight = 1.2;
};

// The cones of P4's expansion as lattice offsets, one table per (step, directions, limits,
// flatness): the children of a lattice point reached along the offset `heading` (in cells),
// independent of where the point is: one per cone direction, snapped to the nearest lattice
// point that keeps the turn and climb limits, duplicates merged. Built on first use and kept;
// several searches (and threads) may share one set: the rendezvous's multi-step search comes
// back to each step and direction count for every UAV, on every engine.
class DirectionalCones {
 public:
  struct Child {
    std::int16_t d[3];
    double length_cells;  // |d|: with the cell size, the segment's length in g
  };
  struct Cone {
    std::vector<Child> children;
    double max_length_cells = 0.0;
  };
  struct Key {
    double step_cells = -1.0, max_yaw_rad = -1.0, max_pitch_rad = -1.0;
    int directions = -1;
    bool flat = false;
    bool operator==(const Key&) const = default;
  };
  struct Table;

  // Thread-safe; references stay valid for the life of this object.
  Table& table(const Key& key);
  const Cone& cone(Table& table, int dx, int dy, int dz);
  // Whether a move that climbs or descends is reachable through the cones from these headings
  // (packed offsets); the headings from which none is are remembered per table.
  bool level_change_reachable(Table& table, const std::vector<std::uint32_t>& headings);

  DirectionalCones();
  ~DirectionalCones();

 private:
  const Cone& cone_locked(Table& table, int dx, int dy, int dz);
  std::mutex mutex_;
  std::vector<std::unique_ptr<Table>> tables_;
};

// Reusable search state (buffers, clearance cache): one per thread; repeated queries on the same
// world (P4's rendezvous runs many) reuse what they can. Engines may share their cone tables.
class DirectionalSearch {
 public:
  explicit DirectionalSearch(std::shared_ptr<DirectionalCones> cones = std::make_shared<DirectionalCones>())
      : cones_(std::move(cones)) {}
  DirectionalRoute run(const World& world, const DirectionalQuery& q, const StopCondition& stop);
  // Bytes held for reuse: search nodes, open list, clearance cache (cone tables not counted).
  std::size_t memory_bytes() const {
    return search_.memory_bytes() + relaxed_dist_.capacity() * sizeof(double) + relaxed_closed_.capacity() +
           relaxed_open_.memory_bytes() + clearance_.capacity() * sizeof(float) +
           cell_opened_.capacity() * sizeof(std::uint32_t);
  }

 private:
  struct Run;  // one search on these buffers (directional_astar.cpp)
  // One search; `count_afresh` false: lattice points opened by the previous search of this
  // query are not counted again (its first, incumbent search).
  DirectionalRoute run_with_bins(const World& world, const DirectionalQuery& q, const StopCondition& stop,
                                 std::uint32_t heading_bins, bool count_afresh = true);
  DirectionalRoute run_bounded_by_incumbent(const World& world, const DirectionalQuery& q, const StopCondition& stop);
  // Whether the search can ever change level: some move from the start, its children, or a cone
  // they lead to climbs or descends.
  bool levels_reachable(const World& world, const DirectionalQuery& q, DirectionalCones::Table& table);
  float clearance_at(const World& world, std::uint32_t point, const Vec3& p, double cap_m);

  BestFirst<> search_;
  // The relaxed heuristic's reverse search (one per query; its own loop: it pauses and resumes):
  // a distance and a closed flag per lattice point (dense: it reads every neighbour of a point,
  // where paged nodes cost a lookup each).
  std::vector<double> relaxed_dist_;
  std::vector<std::uint8_t> relaxed_closed_;
  OpenList relaxed_open_;
  bool relaxed_resumable_ = false;  // the buffers above hold this query's reverse search
  std::shared_ptr<DirectionalCones> cones_;
  // Clearance of lattice points (capped at clearance_cap_m_), for one world and lattice; NaN
  // where not yet computed.
  const World* clearance_world_ = nullptr;
  double clearance_cell_m_ = 0.0, clearance_cap_m_ = 0.0;
  double clearance_origin_z_ = 0.0;  // a one-level lattice lies at its query's start height
  std::vector<float> clearance_;
  // Per lattice point, the query that last put it on the open list (cells_opened), by a stamp.
  std::vector<std::uint32_t> cell_opened_;
  std::uint32_t cell_query_ = 0;
};

class DirectionalAStarPlanner final : public Planner {
 public:
  explicit DirectionalAStarPlanner(DirectionalAStarOptions options = {}) : options_(options) {}
  std::string_view name() const override { return "directional_astar"; }
  const DirectionalAStarOptions& options() const { return options_; }
  // The query this planner would run for a problem (limits and cell resolved).
  DirectionalQuery query_for(const Problem& problem, const World& world) const;
  // Throws std::invalid_argument naming cell_m when `engines` searches on the lattice of q would
  // need more memory than the run's cap (or more points than an index holds).
  static void require_lattice(const World& world, const DirectionalQuery& q, int engines, const StopCondition& stop);

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  DirectionalAStarOptions options_;
};

}  // namespace uavplan
