// P4's directional A* search (DirectionalSearch): the lattice's states, the cone expansion, the
// relaxed heuristic and the incumbent bound.
#include <unordered_map>
#include <unordered_set>

#include "uavplan/core/tolerances.h"
#include "uavplan/planning/search/directional_lattice.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

using namespace directional;

bool DirectionalSearch::levels_reachable(const World& world, const DirectionalQuery& q,
                                         DirectionalCones::Table& table) {
  const Lattice lat = make_lattice(world, q);
  const bool flat = lat.n[2] == 1;
  if (flat) return true;
  const ConeLimits lim(q);
  // Headings of the start's grandchildren (collisions ignored: a superset), then every heading
  // the cone tables lead to from them.
  std::vector<std::uint32_t> headings;
  bool change = false;
  const std::optional<Vec3> h0 = start_heading(q);
  general_children(lat, q, lim, flat, q.start, h0, [&](std::uint32_t, const Vec3& c) {
    if (change) return;
    general_children(lat, q, lim, flat, c, c - q.start, [&](std::uint32_t, const Vec3& g) {
      const Vec3 d = (g - c) / q.cell_m;
      const int dz = static_cast<int>(std::lround(d.z()));
      change = change || dz != 0;
      headings.push_back(pack_offset(static_cast<int>(std::lround(d.x())), static_cast<int>(std::lround(d.y())), dz));
    });
  });
  return change || cones_->level_change_reachable(table, headings);
}

float DirectionalSearch::clearance_at(const World& world, std::uint32_t point, const Vec3& p, double cap_m) {
  float& v = clearance_[point];
  if (std::isnan(v)) {
    const double c = world.clearance(p, cap_m);
    v = static_cast<float>(c);
    if (static_cast<double>(v) > c) v = std::nextafter(v, 0.0f);  // a lower bound, never above
  }
  return v;
}

DirectionalRoute DirectionalSearch::run(const World& world, const DirectionalQuery& q, const StopCondition& stop) {
  if (q.directions > ConeDirections::kMaxPitches) {
    DirectionalRoute r;
    r.fail(Reason::invalid, "directions: at most " + std::to_string(ConeDirections::kMaxPitches));
    return r;
  }
  if (q.incumbent_weight > 1.0 && q.heuristic_weight == 1.0 && !std::isfinite(q.max_length_m))
    return run_bounded_by_incumbent(world, q, stop);
  return run_with_bins(world, q, stop, q.heading_states ? 8 : 1);
}

// The incumbent search, then the exact one bounded by its route (DirectionalQuery::
// incumbent_weight): counts are the two searches' together, lattice points opened by both once.
// Where the first finds no route the exact search runs unbounded (the state's cone depends on the
// arrival that closed it, so the two orders need not reach the same points); where the exact one
// finds none within the bound, or is stopped, the incumbent is the answer: no shorter route was
// left to find, or the caller asked for one now.
DirectionalRoute DirectionalSearch::run_bounded_by_incumbent(const World& world, const DirectionalQuery& q,
                                                             const StopCondition& stop) {
  const std::uint32_t bins = q.heading_states ? 8 : 1;
  DirectionalQuery first = q;
  first.heuristic_weight = q.incumbent_weight;
  DirectionalRoute incumbent = run_with_bins(world, first, stop, bins);
  if (incumbent.reason == Reason::stopped) return incumbent;
  DirectionalQuery exact = q;
  // The bound admits the incumbent's own length whatever the order of the sums.
  if (incumbent.solved()) exact.max_length_m = incumbent.length_m * (1.0 + kRelativeTie) + kRelativeTie * q.cell_m;
  DirectionalRoute r = run_with_bins(world, exact, stop, bins, false);
  add_counts(r, incumbent);
  if (r.solved() || !incumbent.solved()) return r;
  r.succeed();
  r.waypoints = std::move(incumbent.waypoints);
  r.length_m = incumbent.length_m;
  r.message.clear();
  return r;
}

// One search (P4 sec. 2) on an engine's buffers: what it keeps besides them, each part of an
// expansion a method. A state is a lattice point and, with 8 bins, the heading sector it was
// reached in: a point reached with another heading is another state, so a point closed while
// facing a wall can still be passed facing along it.
struct DirectionalSearch::Run {
  Run(DirectionalSearch& engine, const World& w, const DirectionalQuery& query, const StopCondition& st,
      std::uint32_t bins, bool afresh)
      : self(engine),
        world(w),
        q(query),
        stop(st),
        lat(make_lattice(w, query)),
        flat(lat.n[2] == 1),
        start_id(static_cast<std::uint32_t>(lat.size() * bins)),
        goal_id(start_id + 1),
        bin_bits(bins > 1 ? 3u : 0u),  // bins is 1 or 8
        lim(query),
        step_m(query.step_cells * query.cell_m),
        reach(static_cast<int>(std::ceil(query.step_cells)) + 1),
        goal_hop_m(1.5 * step_m + query.cell_m),
        cone_table(engine.cones_->table(
            {query.step_cells, query.max_yaw_rad, query.max_pitch_rad, std::max(1, query.directions), flat})),
        side(2 * reach + 1),
        cone_index(static_cast<std::size_t>(side) * side * side, nullptr),
        stride_y(lat.n[0]),
        stride_z(static_cast<std::int64_t>(lat.n[0]) * lat.n[1]),
        inv_sin_pitch(query.climb_bound ? 1.0 / std::sin(std::min(query.max_pitch_rad + kAngleTolerance_rad, kPi / 2))
                                        : 0.0),
        inv_move_climb(inv_sin_pitch),
        bounded(query.heuristic_weight == 1.0 && std::isfinite(query.max_length_m)),
        count_afresh(afresh) {
    // With a short step no lattice move may keep the climb limit and change level (at 30 deg a
    // level takes sqrt(3) cells across): then a node on a level from which the goal hop cannot
    // reach the goal is a dead end, and a search that must climb ends at once.
    level_locked =
        !flat && std::abs(q.goal.z() - q.start.z()) > goal_hop_m && !engine.levels_reachable(world, q, cone_table);
    prepare_clearances();
    if (q.climb_bound || q.relaxed_heuristic) collect_relaxed_moves();
  }

  DirectionalRoute search();

 private:
  Vec3 position(std::uint32_t id) const {
    return id == start_id ? q.start : id == goal_id ? q.goal : lat.point(id >> bin_bits);
  }
  // Heading sector by octant (signs of x and y, and which is larger): no trigonometry.
  std::uint32_t state_of(std::uint32_t point, const Vec3& seg) const {
    if (bin_bits == 0) return point;
    const std::uint32_t bin =
        (seg.x() < 0 ? 4u : 0u) | (seg.y() < 0 ? 2u : 0u) | (std::abs(seg.x()) < std::abs(seg.y()) ? 1u : 0u);
    return point << bin_bits | bin;
  }
  // Everything but the static world, then the exact check.
  bool segment_limits_ok(const Vec3& a, const Vec3& b) const {
    if (!world.in_bounds(a) || !world.in_bounds(b) || a.z() > q.ceiling_m || b.z() > q.ceiling_m) return false;
    if (!lim.pitch_ok(b - a)) return false;
    for (const Sphere& s : q.virtual_threats)
      if (point_segment_distance(s.center, a, b) < s.radius_m + q.inflation_m) return false;
    return true;
  }
  bool segment_ok(const Vec3& a, const Vec3& b) const {
    return segment_limits_ok(a, b) && !world.segment_collides(a, b, q.inflation_m);
  }
  // Lattice points reached from a lattice point expand through the cone table (children outside
  // the lattice dropped); only the start and its children take the general path. Points at least
  // `reach` cells from every face need no bounds check.
  bool interior(int i, int j, int k) const {
    return i >= reach && i < lat.n[0] - reach && j >= reach && j < lat.n[1] - reach &&
           (flat || (k >= reach && k < lat.n[2] - reach));
  }
  // h: the Euclidean distance (P4 eq. 6); with climb_bound, raised to the least length that can
  // climb |dz|: a lattice move climbs at most 1 / inv_move_climb of its length (the steepest move
  // of the search's cones: 26.6 deg where the limit is 30), the exact last segment to the goal, of
  // at most goal_hop_m, sin(phi_max) (climb_length). Still a lower bound, and consistent along
  // feasible segments; it changes nothing where the climb is gentle and spares a climb-limited
  // search (a spiral up) most of its expansions. h0 is the start's, which leaves by a general
  // move: sin(phi_max) throughout.
  double h(const Vec3& to) const {
    return std::max((q.goal - to).norm(), climb_length(std::abs(q.goal.z() - to.z()), goal_hop_m));
  }
  double h0() const { return std::max((q.goal - q.start).norm(), std::abs(q.goal.z() - q.start.z()) * inv_sin_pitch); }
  // The shortest route that climbs `dz` with one segment of at most `steep_m` at sin(phi_max) and
  // lattice moves at 1 / inv_move_climb.
  double climb_length(double dz, double steep_m) const {
    if (inv_sin_pitch == 0.0) return 0.0;
    const double steep_climb_m = steep_m / inv_sin_pitch;
    return dz <= steep_climb_m ? dz * inv_sin_pitch : steep_m + (dz - steep_climb_m) * inv_move_climb;
  }
  // One clearance per lattice point replaces the segment checks of all its children when it
  // exceeds the longest child plus the inflation (every child segment stays inside that ball).
  void prepare_clearances() {
    const double cap_m = (reach + 1) * q.cell_m + q.inflation_m;
    if (self.clearance_world_ != &world || self.clearance_cell_m_ != q.cell_m || self.clearance_cap_m_ < cap_m ||
        self.clearance_origin_z_ != lat.origin.z() || self.clearance_.size() != static_cast<std::size_t>(lat.size())) {
      self.clearance_world_ = &world;
      self.clearance_cell_m_ = q.cell_m;
      self.clearance_origin_z_ = lat.origin.z();
      self.clearance_cap_m_ = cap_m;
      self.clearance_.assign(static_cast<std::size_t>(lat.size()), std::numeric_limits<float>::quiet_NaN());
    }
  }
  float clearance(std::uint32_t point, const Vec3& p) {
    return self.clearance_at(world, point, p, self.clearance_cap_m_);
  }
  // A move from a to b (a's clearance c_a, b's c_b): clear if the two clearances cover it (every
  // point of it is within clearance - inflation of one end); blocked if b itself is within the
  // inflation (by more than the cache's float rounding); else the exact check.
  bool move_clear(double c_a, double c_b, const Vec3& a, const Vec3& b, double length_m) const {
    if (c_a + c_b - 2 * q.inflation_m >= length_m) return true;
    if (c_b + 1e-6 * (std::abs(c_b) + q.inflation_m) < q.inflation_m) return false;
    return !world.segment_collides(a, b, q.inflation_m);
  }

  // The relaxed problem (DirectionalAStarOptions::relaxed_heuristic): its moves, and its exact
  // distances to the goal by a reverse search toward the start, resumed until the point asked
  // for is closed.
  struct Move {
    std::int16_t d[3];
    double length_m;
  };
  void start_relaxed();
  void collect_relaxed_moves();
  void seed_relaxed_goal();
  double relaxed_distance(std::uint32_t point);
  bool relaxed_edge_ok(std::uint32_t from_pt, const Vec3& from, float c_to, const Vec3& to, double length_m);
  // From a lattice point back to the start, whose move to its child is a general one.
  double relaxed_h(const Vec3& p) const {
    return std::max((q.start - p).norm(), climb_length(std::abs(q.start.z() - p.z()), start_hop_m));
  }

  // The engine's policy (best_first.h): children go in with h, and the relaxed distance raises a
  // node's f as it comes off the list (refine).
  struct Heuristic {
    const Run* run;
    double operator()(const Vec3& to) const { return run->q.heuristic_weight * run->h(to); }
  };
  using Relax = BestFirst<>::Relax<Heuristic>;

 public:
  bool stop_now(std::uint64_t expanded);
  double refine(std::uint32_t id, double f, double g);
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax);

 private:
  void relax(std::uint32_t from, double g_from, std::uint32_t id, const Vec3& to, double length_m);
  void note_opened(std::uint32_t point);
  void begin_cell_count();
  void try_goal(std::uint32_t from, double g_from, const Vec3& p, const std::optional<Vec3>& heading);
  const DirectionalCones::Cone& cone_for(int dx, int dy, int dz);
  void expand_cone(std::uint32_t id, const SearchBuffers::Node& n, int i, int j, int k, const Vec3& p);
  void expand_general(std::uint32_t id, const SearchBuffers::Node& n, const Vec3& p);
  DirectionalRoute finish();

  DirectionalSearch& self;
  const World& world;
  const DirectionalQuery& q;
  const StopCondition& stop;
  const Lattice lat;
  const bool flat;
  const std::uint32_t start_id, goal_id;
  const unsigned bin_bits;
  const ConeLimits lim;
  const double step_m;
  const int reach;
  const double goal_hop_m;
  DirectionalCones::Table& cone_table;
  bool level_locked = false;
  // The cones of this search by heading offset (references into the table stay valid).
  const int side;
  std::vector<const DirectionalCones::Cone*> cone_index;
  const std::int64_t stride_y, stride_z;
  const double inv_sin_pitch;
  double inv_move_climb;  // 1 / the steepest lattice move's climb per length (collect_relaxed_moves)
  // The longest general move (from the start): L cells to the target, snapped within a cell.
  const double start_hop_m = (q.step_cells + std::sqrt(3.0)) * q.cell_m;
  // With f = g + h a lower bound on the length through a node, the length bound prunes.
  const bool bounded;
  const bool count_afresh;  // false: the query's first search counted its points (note_opened)
  bool beyond_bound = false;
  int children = 0;               // of the node being expanded
  Relax* engine_relax = nullptr;  // of the node being expanded
  std::vector<Move> relaxed_moves;
  bool relaxed_started = false, relaxed_stopped = false;
  bool relaxed_reached = false;  // some node the search took had a finite relaxed distance
  DirectionalRoute out;
};

void DirectionalSearch::Run::start_relaxed() {
  relaxed_started = true;
  // The reverse search depends on the goal, not on the forward search's order: the query's second
  // search resumes the first's.
  if (!count_afresh && self.relaxed_resumable_) return;
  self.relaxed_resumable_ = true;
  self.relaxed_dist_.assign(static_cast<std::size_t>(lat.size()), kInfinity);
  self.relaxed_closed_.assign(static_cast<std::size_t>(lat.size()), 0);
  // f of the reverse search starts near the start-goal bound and grows by a fraction of a step
  // per expansion, as the forward search's.
  self.relaxed_open_.reset(std::max(0.0, relaxed_h(q.goal) - goal_hop_m), 0.5 * q.cell_m);
  seed_relaxed_goal();
}

// Every move the forward search can make between lattice points: the general moves of the
// start's children (collisions ignored: a superset), then the children of every cone they lead to.
void DirectionalSearch::Run::collect_relaxed_moves() {
  std::unordered_set<std::uint32_t> seen;
  std::vector<std::uint32_t> frontier;
  auto add = [&](int dx, int dy, int dz) {
    if ((dx != 0 || dy != 0 || dz != 0) && seen.insert(pack_offset(dx, dy, dz)).second) {
      frontier.push_back(pack_offset(dx, dy, dz));
      relaxed_moves.push_back(
          Move{{static_cast<std::int16_t>(dx), static_cast<std::int16_t>(dy), static_cast<std::int16_t>(dz)},
               q.cell_m * Vec3(dx, dy, dz).norm()});
    }
  };
  const std::optional<Vec3> h0 = start_heading(q);
  general_children(lat, q, lim, flat, q.start, h0, [&](std::uint32_t, const Vec3& c) {
    general_children(lat, q, lim, flat, c, c - q.start, [&](std::uint32_t, const Vec3& g) {
      const Vec3 d = (g - c) / q.cell_m;
      add(static_cast<int>(std::lround(d.x())), static_cast<int>(std::lround(d.y())),
          static_cast<int>(std::lround(d.z())));
    });
  });
  while (!frontier.empty()) {
    const std::uint32_t k = frontier.back();
    frontier.pop_back();
    const int dx = static_cast<int>(k >> 20) - 512, dy = static_cast<int>((k >> 10) & 1023) - 512,
              dz = static_cast<int>(k & 1023) - 512;
    for (const DirectionalCones::Child& c : cone_for(dx, dy, dz).children) add(c.d[0], c.d[1], c.d[2]);
  }
  double climb = 0.0;  // per length, of the steepest move
  for (const Move& mv : relaxed_moves) climb = std::max(climb, std::abs(mv.d[2]) * q.cell_m / mv.length_m);
  if (climb > 0.0 && inv_sin_pitch > 0.0) inv_move_climb = std::max(inv_sin_pitch, 1.0 / climb);
}

// The reverse search starts from every lattice point with a clear last segment to the goal (as
// try_goal, less the turn), at its length.
void DirectionalSearch::Run::seed_relaxed_goal() {
  const double r = goal_hop_m;
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, static_cast<int>(std::ceil((q.goal[a] - r - lat.origin[a]) / q.cell_m)));
    hi[a] = std::min(lat.n[a] - 1, static_cast<int>(std::floor((q.goal[a] + r - lat.origin[a]) / q.cell_m)));
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const Vec3 p = lat.at(i, j, k);
        const double d = (q.goal - p).norm();
        if (d > r || !segment_ok(p, q.goal)) continue;
        const std::uint32_t pt = lat.index(i, j, k);
        double& dist = self.relaxed_dist_[pt];
        if (d < dist) {
          dist = d;
          self.relaxed_open_.push(d + relaxed_h(p), d, pt);
        }
      }
}

// The forward search's test of a move between lattice points (expand_cone), less the turn. `c_to`
// is the clearance of the move's end: where it covers the move, the start's is not needed.
bool DirectionalSearch::Run::relaxed_edge_ok(std::uint32_t from_pt, const Vec3& from, float c_to, const Vec3& to,
                                             double length_m) {
  if (from.z() > q.ceiling_m) return false;
  for (const Sphere& sp : q.virtual_threats)
    if (point_segment_distance(sp.center, from, to) < sp.radius_m + q.inflation_m) return false;
  if (static_cast<double>(c_to) - q.inflation_m >= length_m) return true;
  return move_clear(c_to, clearance(from_pt, from), to, from, length_m);
}

// The relaxed problem's distance from `point` to the goal: the reverse search goes on until the
// point is closed (Reverse Resumable A*); infinite where the goal is out of reach.
double DirectionalSearch::Run::relaxed_distance(std::uint32_t point) {
  std::vector<double>& dist = self.relaxed_dist_;
  std::vector<std::uint8_t>& closed = self.relaxed_closed_;
  OpenList& open = self.relaxed_open_;
  if (closed[point]) return dist[point];
  while (!open.empty() && !relaxed_stopped) {
    const OpenList::Entry e = open.pop();
    if (closed[e.id]) continue;
    closed[e.id] = 1;
    const double g = dist[e.id];
    if ((++out.relaxed_expanded & 255) == 0 && stop.should_stop(out.expanded)) relaxed_stopped = true;
    int i, j, k;
    lat.coords(e.id, i, j, k);
    const Vec3 to = lat.at(i, j, k);
    const float c_to = clearance(e.id, to);
    for (const Move& mv : relaxed_moves) {
      const int pi = i - mv.d[0], pj = j - mv.d[1], pk = k - mv.d[2];
      if (pi < 0 || pi >= lat.n[0] || pj < 0 || pj >= lat.n[1] || pk < 0 || pk >= lat.n[2]) continue;
      const auto from_pt = static_cast<std::uint32_t>(e.id - mv.d[0] - mv.d[1] * stride_y - mv.d[2] * stride_z);
      const double ng = g + mv.length_m;
      if (closed[from_pt] || !(ng < dist[from_pt])) continue;
      const Vec3 from = lat.at(pi, pj, pk);
      if (!relaxed_edge_ok(from_pt, from, c_to, to, mv.length_m)) continue;
      dist[from_pt] = ng;
      open.push(ng + relaxed_h(from), ng, from_pt);
    }
    if (e.id == point) return g;
  }
  // Stopped: the Euclidean bound (the forward search stops at its next expansion).
  return relaxed_stopped ? h(lat.point(point)) : kInfinity;
}

// Past max_expansions, or the stop (checked every 256 expansions, and by the relaxed search):
// `out` says which.
bool DirectionalSearch::Run::stop_now(std::uint64_t expanded) {
  out.expanded = expanded;
  if (static_cast<std::int64_t>(out.expanded) <= q.max_expansions && !relaxed_stopped &&
      !((out.expanded & 255) == 0 && stop.should_stop(out.expanded)))
    return false;
  if (static_cast<std::int64_t>(out.expanded) <= q.max_expansions)
    out.fail(Reason::stopped, "stopped before a route was found");
  else
    out.fail(Reason::budget, "expansion limit reached (planner.params.max_expansions = " +
                                 std::to_string(q.max_expansions) + "; raise it, or give a larger cell_m)");
  return true;
}

void DirectionalSearch::Run::relax(std::uint32_t from, double g_from, std::uint32_t id, const Vec3& to,
                                   double length_m) {
  const double ng = g_from + length_m;
  // Never popped before the search gives up: not worth a place in the list.
  if (bounded && ng + h(to) > q.max_length_m) {
    beyond_bound = true;
    return;
  }
  if ((*engine_relax)(id, ng, from, to) && id < start_id) note_opened(id >> bin_bits);
}

void DirectionalSearch::Run::note_opened(std::uint32_t point) {
  std::uint32_t& stamp = self.cell_opened_[point];
  if (stamp != self.cell_query_) {
    stamp = self.cell_query_;
    ++out.cells_opened;
  }
}

void DirectionalSearch::Run::begin_cell_count() {
  if (++self.cell_query_ == 0 || self.cell_opened_.size() != static_cast<std::size_t>(lat.size())) {
    self.cell_opened_.assign(static_cast<std::size_t>(lat.size()), 0);
    self.cell_query_ = 1;
  }
}

// A lattice node coming off the list: f with the relaxed distance (at least h: it is the length
// of a route of real segments); infinite where the goal is out of reach even without turn limits,
// or beyond the length bound.
double DirectionalSearch::Run::refine(std::uint32_t id, double f, double g) {
  if (!q.relaxed_heuristic || id >= start_id) return f;
  if (!relaxed_started) start_relaxed();
  const double left = relaxed_distance(id >> bin_bits);
  relaxed_reached = relaxed_reached || left < kInfinity;
  if (bounded && g + left > q.max_length_m) {
    beyond_bound = true;
    return kInfinity;
  }
  return std::max(f, g + q.heuristic_weight * left);
}

// Within reach of the goal: the last segment to the exact goal.
void DirectionalSearch::Run::try_goal(std::uint32_t from, double g_from, const Vec3& p,
                                      const std::optional<Vec3>& heading) {
  const Vec3 to_goal = q.goal - p;
  if (to_goal.norm() <= 1.5 * step_m + q.cell_m && lim.turn_ok(heading, to_goal) && segment_ok(p, q.goal)) {
    ++children;
    relax(from, g_from, goal_id, q.goal, to_goal.norm());
  }
}

const DirectionalCones::Cone& DirectionalSearch::Run::cone_for(int dx, int dy, int dz) {
  if (std::abs(dx) > reach || std::abs(dy) > reach || std::abs(dz) > reach)
    return self.cones_->cone(cone_table, dx, dy, dz);
  const auto offset = [this](int d) {
    const int from_corner = d + reach;  // in [0, side)
    return static_cast<std::size_t>(from_corner);
  };
  const auto width = static_cast<std::size_t>(side);
  const DirectionalCones::Cone*& slot = cone_index[(offset(dz) * width + offset(dy)) * width + offset(dx)];
  if (!slot) slot = &self.cones_->cone(cone_table, dx, dy, dz);
  return *slot;
}

// A lattice point reached from a lattice point: the children of the cone of its heading.
void DirectionalSearch::Run::expand_cone(std::uint32_t id, const SearchBuffers::Node& n, int i, int j, int k,
                                         const Vec3& p) {
  const std::uint32_t pt = id >> bin_bits;
  const bool inside = interior(i, j, k);
  int pi, pj, pk;
  lat.coords(n.parent >> bin_bits, pi, pj, pk);
  const DirectionalCones::Cone& cn = cone_for(i - pi, j - pj, k - pk);
  const double max_len_m = cn.max_length_cells * q.cell_m;
  const float clearance_p = clearance(pt, p);
  const bool all_clear = clearance_p >= max_len_m + q.inflation_m;
  bool near_virtual = false;
  for (const Sphere& sp : q.virtual_threats)
    near_virtual = near_virtual || (sp.center - p).norm() - max_len_m < sp.radius_m + q.inflation_m;
  for (const DirectionalCones::Child& c : cn.children) {
    if (!inside && (i + c.d[0] < 0 || i + c.d[0] >= lat.n[0] || j + c.d[1] < 0 || j + c.d[1] >= lat.n[1] ||
                    k + c.d[2] < 0 || k + c.d[2] >= lat.n[2]))
      continue;
    const Vec3 to = p + q.cell_m * Vec3(c.d[0], c.d[1], c.d[2]);
    if (to.z() > q.ceiling_m) continue;
    if (near_virtual && std::any_of(q.virtual_threats.begin(), q.virtual_threats.end(), [&](const Sphere& sp) {
          return point_segment_distance(sp.center, p, to) < sp.radius_m + q.inflation_m;
        }))
      continue;
    const auto child_pt = static_cast<std::uint32_t>(pt + c.d[0] + c.d[1] * stride_y + c.d[2] * stride_z);
    if (!all_clear && !move_clear(clearance_p, clearance(child_pt, to), p, to, c.length_cells * q.cell_m)) continue;
    ++children;
    // g adds the lattice length of the move, cell |d|, not |to - p|: the same for every point,
    // free of the rounding of positions far from the origin.
    relax(id, n.g, state_of(child_pt, to - p), to, c.length_cells * q.cell_m);
  }
  try_goal(id, n.g, p, p - lat.at(pi, pj, pk));
}

// The start and its children: moves within the limits around the heading (general_children).
// The start's children are lattice points: their clearances may cover a segment between two
// lattice points as in the cone path.
void DirectionalSearch::Run::expand_general(std::uint32_t id, const SearchBuffers::Node& n, const Vec3& p) {
  std::optional<Vec3> heading;
  if (id == start_id) {
    heading = start_heading(q);
  } else {
    heading = p - position(n.parent);
  }
  const float clearance_p = id == start_id ? 0.0f : clearance(id >> bin_bits, p);
  general_children(lat, q, lim, flat, p, heading, [&](std::uint32_t child, const Vec3& to) {
    const double len_m = (to - p).norm();
    const bool covered = id != start_id && len_m <= (reach + 1) * q.cell_m &&
                         static_cast<double>(clearance_p) + clearance(child, to) - 2 * q.inflation_m >= len_m;
    if (covered ? segment_limits_ok(p, to) : segment_ok(p, to)) {
      ++children;
      relax(id, n.g, state_of(child, to - p), to, len_m);
    }
  });
  try_goal(id, n.g, p, heading);
}

void DirectionalSearch::Run::expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) {
  engine_relax = &relax;
  int i = 0, j = 0, k = 0;  // the lattice coordinates of a lattice node
  if (id < start_id) lat.coords(id >> bin_bits, i, j, k);
  const Vec3 p = id < start_id ? lat.at(i, j, k) : position(id);
  children = 0;
  if (id != start_id && n.parent != start_id) {
    if (level_locked && std::abs(q.goal.z() - p.z()) > goal_hop_m) {
      ++out.dead_zones;
      return;
    }
    expand_cone(id, n, i, j, k, p);
  } else {
    expand_general(id, n, p);
  }
  if (children == 0) ++out.dead_zones;  // closed; the next best node is taken (P4 eq. 7)
}

DirectionalRoute DirectionalSearch::Run::search() {
  const double h0 = this->h0();
  // Children beyond the length bound are never pushed: only the start can be.
  if (bounded && h0 > q.max_length_m) {
    out.fail(Reason::no_route, "no route within the length bound");
    return std::move(out);
  }
  // f grows by a fraction of a step per expansion: buckets of half a cell hold a few hundred
  // entries each.
  self.search_.begin(lat.size() * (bin_bits ? 8 : 1) + 2, h0, 0.5 * q.cell_m);
  if (count_afresh) {
    begin_cell_count();
    self.relaxed_resumable_ = false;
  }
  SearchCounts counts;
  const SearchEnd end =
      self.search_.run(*this, Heuristic{this}, start_id, SearchBuffers::kNoParent, q.start, goal_id, counts);
  out.generated = counts.generated;
  out.opened = counts.opened;
  out.open_max = counts.open_max;
  if (end == SearchEnd::stopped) return std::move(out);
  return finish();
}

// The route back from the goal, or why there is none.
DirectionalRoute DirectionalSearch::Run::finish() {
  const SearchBuffers::Node& goal = self.search_.node(goal_id);
  if (!SearchBuffers::closed(goal)) {
    out.reason = Reason::no_route;
    if (beyond_bound)
      out.message = "no route within the length bound";
    else if (relaxed_started && !relaxed_reached)
      out.message =
          "no route within the turn and climb limits: no lattice route reaches the goal even without the turn "
          "limits (obstacles, the bounds, the ceiling or the climb limit close it off); " +
          limits_hint(q, flat);
    else
      out.message = "no route within the turn and climb limits (" + std::to_string(out.dead_zones) + " dead zones); " +
                    limits_hint(q, flat);
    return std::move(out);
  }
  out.succeed();
  out.length_m = goal.g;
  for (const std::int64_t id : self.search_.path(start_id, goal_id))
    out.waypoints.push_back(position(static_cast<std::uint32_t>(id)));
  return std::move(out);
}

DirectionalRoute DirectionalSearch::run_with_bins(const World& world, const DirectionalQuery& q,
                                                  const StopCondition& stop, std::uint32_t bins, bool count_afresh) {
  const std::int64_t states = make_lattice(world, q).size() * bins;
  if (states + 2 >= static_cast<std::int64_t>(SearchBuffers::kNoParent)) {
    DirectionalRoute out;
    out.fail(Reason::budget, "lattice too large; give a larger cell_m");
    return out;
  }
  return Run(*this, world, q, stop, bins, count_afresh).search();
}

}  // namespace uavplan
