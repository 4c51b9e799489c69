#include "uavplan/coordination/spacetime/uav_lattice.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "uavplan/coordination/spacetime/mapf.h"
#include "uavplan/core/geometry.h"

namespace uavplan {

std::uint64_t lattice_cell_count(const Aabb& bounds, double cell_m) {
  const Vec3 size = bounds.max - bounds.min;
  const auto count = [&](double s) { return std::max(1.0, std::floor(s / cell_m) + 1.0); };
  const double n = count(size.x()) * count(size.y()) * count(size.z());
  return n >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : static_cast<std::uint64_t>(n);
}

namespace {

constexpr int kWait = 13;  // direction index of (0, 0, 0)

int direction_index(const Eigen::Vector3i& d) { return (d.z() + 1) * 9 + (d.y() + 1) * 3 + (d.x() + 1); }
Eigen::Vector3i direction(int index) { return {index % 3 - 1, index / 3 % 3 - 1, index / 9 - 1}; }

double pitch_of(const Eigen::Vector3i& d) {
  return std::atan2(std::abs(static_cast<double>(d.z())), std::hypot(d.x(), d.y()));
}

struct Cells {
  const UavLattice& l;
  bool inside(const Eigen::Vector3i& c) const {
    return c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() < l.nx && c.y() < l.ny && c.z() < l.nz;
  }
  int vertex(const Eigen::Vector3i& c) const { return (c.z() * l.ny + c.y()) * l.nx + c.x(); }
  Eigen::Vector3i cell(int v) const { return {v % l.nx, v / l.nx % l.ny, v / (l.nx * l.ny)}; }
};

// The cell at or below p on every axis.
Eigen::Vector3i cell_below(const UavLattice& l, const Vec3& p) {
  const Vec3 f = ((p - l.origin) / l.cell_m).array().floor().matrix();
  return f.cast<int>();
}

// The lattice's cells with their positions, free where a body fits and below the ceiling.
void place_cells(const World& world, const UavLatticeOptions& o, UavLattice& l, std::vector<double>& clear) {
  const Aabb& b = world.bounds();
  const Vec3 size = b.max - b.min;
  const auto count = [&](double s) { return std::max(1, static_cast<int>(std::floor(s / l.cell_m)) + 1); };
  l.nx = count(size.x());
  l.ny = count(size.y());
  l.nz = count(size.z());
  const std::uint64_t cells = static_cast<std::uint64_t>(l.nx) * l.ny * l.nz;
  if (cells > static_cast<std::uint64_t>(SpaceTimeTable::kMostVertices))
    throw std::invalid_argument("a space-time lattice of " + std::to_string(l.nx) + " x " + std::to_string(l.ny) +
                                " x " + std::to_string(l.nz) + " cells is more than " +
                                std::to_string(SpaceTimeTable::kMostVertices) + "; set a larger space_time_cell_m");
  // Centred in the bounds: the cells' span is (n - 1) cells.
  l.origin = b.min + 0.5 * (size - l.cell_m * Vec3(l.nx - 1, l.ny - 1, l.nz - 1));
  const double cap = o.body_m + std::sqrt(3.0) * l.cell_m;
  l.position.resize(static_cast<std::size_t>(cells));
  clear.assign(static_cast<std::size_t>(cells), -1.0);  // < 0: not a free cell
  for (int k = 0; k < l.nz; ++k)
    for (int j = 0; j < l.ny; ++j)
      for (int i = 0; i < l.nx; ++i) {
        const int v = (k * l.ny + j) * l.nx + i;
        const Vec3 p = l.origin + l.cell_m * Vec3(i, j, k);
        l.position[v] = p;
        if (!world.in_bounds(p) || p.z() > o.ceiling_z) continue;
        const double c = world.clearance(p, cap);
        if (c >= o.body_m) clear[v] = c;
      }
}

// Whether the segment a -> b keeps the body clear, from the clearance at a when that suffices.
bool edge_clear(const World& world, const Vec3& a, double clear_a, const Vec3& b, double body_m) {
  if (clear_a >= body_m + (b - a).norm()) return true;  // every point of it is within its length of a
  return world.segment_valid(a, b, body_m);
}

// Moves from each vertex to `goal` through the lattice (the UAVs' points are ends, never passed
// through); -1 where it cannot be reached.
std::vector<int> lattice_distances(const UavLattice& l, int goal) {
  const SpaceTimeGraph& g = l.graph;
  std::vector<int> d(static_cast<std::size_t>(g.vertex_count), -1);
  std::vector<int> queue{goal};
  d[goal] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int u = queue[head];
    if (u != goal && !l.is_cell(u)) continue;  // a point: reached, not passed through
    for (int k = g.first[u]; k < g.first[u + 1]; ++k)
      if (d[g.next[k]] < 0) {
        d[g.next[k]] = d[u] + 1;
        queue.push_back(g.next[k]);
      }
  }
  return d;
}

// Each vertex's connected component (the graph is undirected).
std::vector<int> components(const SpaceTimeGraph& g) {
  std::vector<int> c(static_cast<std::size_t>(g.vertex_count), -1);
  std::vector<int> queue;
  for (int s = 0; s < g.vertex_count; ++s) {
    if (c[s] >= 0) continue;
    c[s] = s;
    queue.assign(1, s);
    for (std::size_t head = 0; head < queue.size(); ++head)
      for (int k = g.first[queue[head]]; k < g.first[queue[head] + 1]; ++k)
        if (c[g.next[k]] < 0) {
          c[g.next[k]] = s;
          queue.push_back(g.next[k]);
        }
  }
  return c;
}

// A lower bound on the moves from each vertex to `goal` through the lattice, exact in open space
// round a goal whose neighbouring cells are free: a lattice vertex needs its Chebyshev distance
// (in cells) to the box of the goal's lattice neighbours, and one move more; a UAV's point one
// move more than its best neighbour. -1 off the goal's component.
std::vector<int> tick_bounds(const UavLattice& l, const std::vector<int>& component, int goal) {
  const SpaceTimeGraph& g = l.graph;
  const Cells at{l};
  Eigen::Vector3i lo = Eigen::Vector3i::Constant(INT_MAX), hi = Eigen::Vector3i::Constant(INT_MIN);
  for (int k = g.first[goal]; k < g.first[goal + 1]; ++k)
    if (l.is_cell(g.next[k])) {
      lo = lo.cwiseMin(at.cell(g.next[k]));
      hi = hi.cwiseMax(at.cell(g.next[k]));
    }
  std::vector<int> h(l.position.size(), -1);
  const int cells = l.cell_count();
  for (int v = 0; v < cells; ++v) {
    if (component[v] != component[goal]) continue;
    if (lo.x() > hi.x()) {  // no lattice neighbour: it is reached from points only
      h[v] = 0;
      continue;
    }
    const Eigen::Vector3i c = at.cell(v);
    h[v] = (lo - c).cwiseMax(c - hi).cwiseMax(0).maxCoeff() + 1;
  }
  for (int v = cells; v < g.vertex_count; ++v) {
    if (component[v] != component[goal]) continue;
    int best = INT_MAX;
    for (int k = g.first[v]; k < g.first[v + 1]; ++k)
      if (l.is_cell(g.next[k])) best = std::min(best, h[g.next[k]]);
    h[v] = best == INT_MAX ? 1 : best + 1;
  }
  h[goal] = 0;
  return h;
}

// Whether a body at p moving at v is beyond the lattice's reach for good (linear motion away).
bool gone(const Aabb& bounds, const Vec3& p, const Vec3& v, double need_m) {
  for (int a = 0; a < 3; ++a) {
    if (p[a] < bounds.min[a] - need_m && v[a] <= 0.0) return true;
    if (p[a] > bounds.max[a] + need_m && v[a] >= 0.0) return true;
  }
  return false;
}

// Whether a UAV may fly straight from a to b in one move: within a lattice diagonal, its climb
// limit, and clear of obstacles by the body.
bool joinable(const World& world, const Vec3& a, const Vec3& b, double cell_m, const UavLatticeOptions& o) {
  const Vec3 step = b - a;
  if (step.norm() > std::sqrt(3.0) * cell_m || step.norm() < kSamePoint_m) return false;
  if (std::atan2(std::abs(step.z()), step.head<2>().norm()) > o.max_climb_rad + 1e-9) return false;
  return world.segment_valid(a, b, o.body_m);
}

// The UAVs' points as vertices after the cells, each joined both ways to the free cells of the
// 4 x 4 x 4 block round it, and to the points before it, that it may fly to in one move.
void join_points(const World& world, std::span<const Vec3> points, const UavLatticeOptions& o,
                 const std::vector<double>& clear, UavLattice& l, std::vector<std::vector<int>>& next) {
  const int cells = l.cell_count();
  const Cells at{l};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int pv = cells + static_cast<int>(i);
    const Vec3& p = points[i];
    l.position.push_back(p);
    const Eigen::Vector3i lo = cell_below(l, p) - Eigen::Vector3i::Ones();
    for (int dz = 0; dz < 4; ++dz)
      for (int dy = 0; dy < 4; ++dy)
        for (int dx = 0; dx < 4; ++dx) {
          const Eigen::Vector3i n = lo + Eigen::Vector3i(dx, dy, dz);
          if (!at.inside(n) || clear[at.vertex(n)] < 0.0) continue;
          const int u = at.vertex(n);
          if (!joinable(world, p, l.position[u], l.cell_m, o)) continue;
          next[pv].push_back(u);
          next[u].push_back(pv);
        }
    for (std::size_t k = 0; k < i; ++k)
      if (joinable(world, p, points[k], l.cell_m, o)) {
        next[pv].push_back(cells + static_cast<int>(k));
        next[cells + static_cast<int>(k)].push_back(pv);
      }
  }
}

}  // namespace

Aabb LatticeAgents::lattice_bounds() const {
  Aabb b;
  for (const Vec3& p : lattice_.position) b.extend(p);
  const double reach = std::max(lattice_.longest_edge_m, std::sqrt(3.0) * lattice_.cell_m);
  b.min -= Vec3::Constant(reach);
  b.max += Vec3::Constant(reach);
  return b;
}

// The direction of the path's last move (`start` when it has none).
Vec3 LatticeAgents::arrival_direction(const SpaceTimePath& path, const Vec3& start) const {
  for (std::size_t k = path.size(); k-- > 1;)
    if (path[k] != path[k - 1]) return lattice_.position[path[k]] - lattice_.position[path[k - 1]];
  return start;
}

double lattice_cell_m(const Aabb& bounds, double need_m) {
  const Vec3 size = (bounds.max - bounds.min).cwiseMax(Vec3::Constant(1e-9));
  const double coarse = std::cbrt(size.x() * size.y() * size.z() / kLatticeCells);
  return std::max(1.05 * need_m, coarse);
}

UavLattice build_uav_lattice(const World& world, std::span<const Vec3> points, const UavLatticeOptions& o,
                             const StopCondition& stop) {
  UavLattice l;
  l.cell_m = o.cell_m > 0.0 ? o.cell_m : lattice_cell_m(world.bounds(), o.need_m);
  std::vector<double> clear;
  place_cells(world, o, l, clear);
  const int cells = l.cell_count();
  if (static_cast<std::uint64_t>(cells) + points.size() > static_cast<std::uint64_t>(SpaceTimeTable::kMostVertices))
    throw std::invalid_argument("too many vertices for a space-time lattice; set a larger space_time_cell_m");
  const Cells at{l};
  std::vector<int> dirs;  // the 26 directions a UAV may fly (its climb limit)
  for (int d = 0; d < 27; ++d)
    if (d != kWait && pitch_of(direction(d)) <= o.max_climb_rad + 1e-9) dirs.push_back(d);
  // Neighbours of each vertex, built as lists, then packed into compressed rows.
  std::vector<std::vector<int>> next(static_cast<std::size_t>(cells) + points.size());
  for (int v = 0; v < cells; ++v) {
    if ((v & 4095) == 0 && stop.should_stop()) throw std::runtime_error("stopped");
    if (clear[v] < 0.0) continue;
    const Eigen::Vector3i c = at.cell(v);
    for (const int d : dirs) {
      const Eigen::Vector3i n = c + direction(d);
      if (!at.inside(n)) continue;
      const int u = at.vertex(n);
      if (clear[u] >= 0.0 && edge_clear(world, l.position[v], clear[v], l.position[u], o.body_m)) next[v].push_back(u);
    }
  }
  join_points(world, points, o, clear, l, next);
  l.graph.vertex_count = static_cast<int>(next.size());
  l.graph.first.assign(next.size() + 1, 0);
  for (std::size_t v = 0; v < next.size(); ++v) {
    std::sort(next[v].begin(), next[v].end());
    l.graph.first[v + 1] = l.graph.first[v] + static_cast<int>(next[v].size());
    for (const int u : next[v]) {
      l.graph.next.push_back(u);
      l.longest_edge_m = std::max(l.longest_edge_m, (l.position[u] - l.position[v]).norm());
    }
  }
  return l;
}

LatticeAgents::LatticeAgents(const UavLattice& lattice, std::vector<LatticeAgent> agents, double need_m, int threads)
    : lattice_(lattice), agents_(std::move(agents)), need_m_(need_m), patterns_(27) {
  reach_m_ = need_m_ + std::max(lattice_.longest_edge_m, std::sqrt(3.0) * lattice_.cell_m);
  for (const LatticeAgent& a : agents_)
    for (const int t : a.targets) to_target_[t];
  const std::size_t targets = to_target_.size();
  const std::uint64_t bytes = sizeof(int) * static_cast<std::uint64_t>(targets) * lattice_.graph.vertex_count;
  if (bytes > kMostDistanceTableBytes)
    throw std::invalid_argument(
        std::to_string(targets) + " distinct targets on a lattice of " + std::to_string(lattice_.graph.vertex_count) +
        " vertices need " + std::to_string(bytes >> 20) + " MiB of distance tables; set a larger space_time_cell_m");
  // Exact distances (one breadth-first sweep per target) where they are few enough; else a bound
  // in closed form within the graph's components: the sweeps would cost more than the
  // expansions the exact distances save.
  const bool exact = static_cast<std::uint64_t>(targets) * lattice_.graph.vertex_count <= kExactTableEntries;
  const std::vector<int> component = exact ? std::vector<int>{} : components(lattice_.graph);
  std::vector<std::vector<int>*> tables;
  std::vector<int> sources;
  for (auto& [t, h] : to_target_) {
    sources.push_back(t);
    tables.push_back(&h);
  }
  const auto sweep = [&](std::size_t first, std::size_t step) {
    for (std::size_t k = first; k < sources.size(); k += step)
      *tables[k] = exact ? lattice_distances(lattice_, sources[k]) : tick_bounds(lattice_, component, sources[k]);
  };
  const std::size_t workers =
      std::clamp<std::size_t>(static_cast<std::size_t>(threads), 1, std::max<std::size_t>(sources.size(), 1));
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(sweep, w, workers);
  sweep(0, workers);
  for (std::thread& t : pool) t.join();
  for (const LatticeAgent& a : agents_) {
    int cost = 0, from = a.start;
    for (const int t : a.targets) {
      const int d = to_target_.at(t)[from];
      if (d < 0) {
        cost = -1;
        break;
      }
      cost += d;
      from = t;
    }
    lone_.push_back(cost);
  }
}

// Leg after leg; each starts where and when the one before ended.
SpaceTimeAnswer LatticeAgents::plan(int agent, const SpaceTimeTable& forbidden, const SpaceTimeTable* avoided, double w,
                                    SpaceTimeSearches& search, const StopCondition& stop) const {
  const LatticeAgent& a = agents_[agent];
  SpaceTimeAnswer out;
  out.path.push_back(a.start);
  for (std::size_t k = 0; k < a.targets.size(); ++k) {
    SpaceTimeQuery q{out.path.back(), a.targets[k], &to_target_.at(a.targets[k]), &forbidden, avoided, w};
    q.start_t = static_cast<int>(out.path.size()) - 1;
    q.stays = k + 1 == a.targets.size();
    q.position = &lattice_.position;
    q.max_turn_rad = a.max_turn_rad;
    q.heading = arrival_direction(out.path, a.heading);
    q.terminals_from = lattice_.cell_count();  // no path passes through another UAV's point
    q.fixed = has_moving_ ? &moving_ : nullptr;
    // Hard constraints alone (prioritised planning): safe intervals; else the focal search.
    SpaceTimeAnswer leg = avoided == nullptr && w == 1.0 ? search.intervals.find(lattice_.graph, q, stop)
                                                         : search.expanded.find(lattice_.graph, q, stop);
    out.expanded += leg.expanded;
    if (!leg.found) {
      out.found = false;
      out.path.clear();
      return out;
    }
    out.path.insert(out.path.end(), leg.path.begin() + 1, leg.path.end());
    out.meetings += leg.meetings;
    out.lower_bound = leg.lower_bound;  // the last leg's, from where the legs before left it
  }
  out.found = true;
  out.cost = static_cast<int>(out.path.size()) - 1;
  out.lower_bound = std::min(out.lower_bound, out.cost);
  return out;
}

bool LatticeAgents::moves_conflict(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) const {
  return point_segment_distance(Vec3::Zero(), a0 - b0, a1 - b1) < need_m_;
}

// A lattice direction's conflicts, as offsets from its start cell, measured once at the origin.
void LatticeAgents::shift_pattern(int u, int v, Entries& out) const {
  const Cells at{lattice_};
  const Eigen::Vector3i cu = at.cell(u);
  const Eigen::Vector3i step = at.cell(v) - cu;
  Pattern& p = patterns_[direction_index(step)];
  if (!p.made) {
    const double c = lattice_.cell_m;
    const Vec3 m = c * step.cast<double>();
    const int r = static_cast<int>(std::ceil(reach_m_ / c)) + 1;
    for (int z = -r; z <= r; ++z)
      for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
          const Eigen::Vector3i o(x, y, z);
          const Vec3 b0 = c * o.cast<double>();
          if (b0.norm() < need_m_) {
            p.vertices.push_back(o);
            continue;
          }
          for (int d = 0; d < 27; ++d) {
            const Vec3 b1 = b0 + c * direction(d).cast<double>();
            if ((b1 - m).norm() >= need_m_ && moves_conflict(Vec3::Zero(), m, b0, b1)) p.moves.emplace_back(o, d);
          }
        }
    p.made = true;
  }
  for (const Eigen::Vector3i& o : p.vertices)
    if (at.inside(cu + o)) out.vertices.push_back(at.vertex(cu + o));
  for (const auto& [o, d] : p.moves) {
    const Eigen::Vector3i x = cu + o, y = x + direction(d);
    if (at.inside(x) && at.inside(y) && lattice_.graph.degree(at.vertex(x)) > 0)
      out.moves.emplace_back(at.vertex(x), at.vertex(y));
  }
}

// What a body moving a0 -> a1 in one step forbids the agents (centres closer than `need_m`):
// being at a vertex near a0 at the step's start, and moves from the vertices near it (from the
// UAVs' points only, unless `cells`); with `ends_next`, only moves whose ends keep clear of a1
// (the next step's entries forbid the others: the same need in every step).
void LatticeAgents::measure_near(const Vec3& a0, const Vec3& a1, double need_m, bool cells, bool ends_next,
                                 Entries& out) const {
  const SpaceTimeGraph& g = lattice_.graph;
  const auto consider = [&](int x) {
    const Vec3& b0 = lattice_.position[x];
    if ((b0 - a0).norm() < need_m) {
      out.vertices.push_back(x);
      return;
    }
    const auto move = [&](int y) {
      const Vec3& b1 = lattice_.position[y];
      if ((!ends_next || (b1 - a1).norm() >= need_m) && point_segment_distance(Vec3::Zero(), a0 - b0, a1 - b1) < need_m)
        out.moves.emplace_back(x, y);
    };
    move(x);
    for (int k = g.first[x]; k < g.first[x + 1]; ++k) move(g.next[k]);
  };
  Aabb box = Aabb::of(a0, a1);
  const double reach = need_m + std::max(lattice_.longest_edge_m, std::sqrt(3.0) * lattice_.cell_m);
  box.min -= Vec3::Constant(reach);
  box.max += Vec3::Constant(reach);
  for (int x = lattice_.cell_count(); x < g.vertex_count; ++x)
    if (box.contains(lattice_.position[x])) consider(x);
  if (!cells) return;
  const Cells at{lattice_};
  const Eigen::Vector3i lo = cell_below(lattice_, box.min);
  const Eigen::Vector3i hi = cell_below(lattice_, box.max) + Eigen::Vector3i::Ones();
  for (int z = std::max(lo.z(), 0); z <= std::min(hi.z(), lattice_.nz - 1); ++z)
    for (int y = std::max(lo.y(), 0); y <= std::min(hi.y(), lattice_.ny - 1); ++y)
      for (int x = std::max(lo.x(), 0); x <= std::min(hi.x(), lattice_.nx - 1); ++x) {
        const int c = at.vertex({x, y, z});
        if (g.degree(c) > 0) consider(c);
      }
}

// The conflicts of u -> v with moves from and to the UAVs' own points near it (and, when u or v
// is one of them, with every lattice move near it).
void LatticeAgents::add_near_points(int u, int v, Entries& out) const {
  const Vec3& a0 = lattice_.position[u];
  const Vec3& a1 = lattice_.position[v];
  const bool lattice_move = lattice_.is_cell(u) && lattice_.is_cell(v);
  measure_near(a0, a1, need_m_, !lattice_move, true, out);
  if (!lattice_move) return;
  // A lattice move's pattern lists only lattice moves, and the points' own moves are measured
  // above: the moves from lattice vertices into points near it are left.
  const SpaceTimeGraph& g = lattice_.graph;
  Aabb box = Aabb::of(a0, a1);
  box.min -= Vec3::Constant(reach_m_);
  box.max += Vec3::Constant(reach_m_);
  for (int p = lattice_.cell_count(); p < g.vertex_count; ++p) {
    if (!box.contains(lattice_.position[p])) continue;
    for (int k = g.first[p]; k < g.first[p + 1]; ++k) {
      const int x = g.next[k];
      if (!lattice_.is_cell(x)) continue;
      const Vec3& b0 = lattice_.position[x];
      if ((b0 - a0).norm() >= need_m_ && (lattice_.position[p] - a1).norm() >= need_m_ &&
          moves_conflict(a0, a1, b0, lattice_.position[p]))
        out.moves.emplace_back(x, p);
    }
  }
}

// Moving obstacles tick by tick from t0: what each forbids in its step (a corner of its path
// within a step widens it by how far the obstacle strays from moving evenly), and where it stops,
// for ever.
void LatticeAgents::keep_off_moving(const std::vector<MovingObstacle>& obstacles, double keep_m, double t0_s,
                                    double tick_s) {
  if (obstacles.empty()) return;
  moving_.clear(lattice_.graph.vertex_count);
  has_moving_ = true;
  const Aabb& bounds = lattice_bounds();
  for (const MovingObstacle& m : obstacles) {
    const double end_s = m.path.empty() ? World::kInf : m.path.back().t_s;
    for (int k = 0; k < kMostMovingTicks; ++k) {
      const double ta = t0_s + k * tick_s, tb = ta + tick_s;
      const Vec3 a0 = m.position_at(ta), a1 = m.position_at(tb);
      // How far the obstacle strays within the step from where moving a0 -> a1 evenly would put
      // it at the same time: the most at one of its path's corners (the difference is
      // piecewise linear in time, zero at both ends).
      double bend = 0.0;
      for (const TimedPoint& r : m.rows())
        if (r.t_s > ta && r.t_s < tb) bend = std::max(bend, (r.p - (a0 + (r.t_s - ta) / tick_s * (a1 - a0))).norm());
      const double need = m.radius_m + keep_m + bend + kMovingMargin_m;
      Entries e;
      const bool still = ta >= end_s || (m.path.empty() && m.velocity_mps.isZero());
      if (still || (m.path.empty() && gone(bounds, a0, m.velocity_mps, need))) {
        if (still) {
          measure_near(a0, a0, need, true, true, e);
          for (const int x : e.vertices) moving_.add_stay(x, k);
          for (const auto& [x, y] : e.moves) moving_.add_move_stay(x, y, k);
        }
        break;
      }
      measure_near(a0, a1, need, true, false, e);  // the need may change from step to step
      for (const int x : e.vertices) moving_.add_vertex(x, k);
      for (const auto& [x, y] : e.moves) moving_.add_move(x, y, k);
    }
  }
}

void LatticeAgents::measure(int u, int v, Entries& out) const {
  if (lattice_.is_cell(u) && lattice_.is_cell(v)) shift_pattern(u, v, out);
  add_near_points(u, v, out);
}

const LatticeAgents::Entries& LatticeAgents::entries_of(int u, int v) const {
  const std::uint64_t key =
      static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32 | static_cast<std::uint32_t>(v);
  auto it = entries_.find(key);
  if (it != entries_.end()) return it->second;
  Entries e;
  measure(u, v, e);
  return entries_.emplace(key, std::move(e)).first->second;
}

void LatticeAgents::add_path(int /*agent*/, const SpaceTimePath& path, SpaceTimeTable& table) const {
  const int end = static_cast<int>(path.size()) - 1;
  for (int t = 0; t < end; ++t) {
    const Entries& e = entries_of(path[t], path[t + 1]);
    for (const int x : e.vertices) table.add_vertex(x, t);
    for (const auto& [x, y] : e.moves) table.add_move(x, y, t);
  }
  const Entries& stay = entries_of(path[end], path[end]);  // it waits at its goal for ever
  for (const int x : stay.vertices) table.add_stay(x, end);
  for (const auto& [x, y] : stay.moves) table.add_move_stay(x, y, end);
}

int LatticeAgents::scan(const std::vector<SpaceTimePath>& paths, bool first, PathConflict* out) const {
  const int n = static_cast<int>(paths.size());
  int horizon = 0;
  for (const SpaceTimePath& p : paths) horizon = std::max(horizon, static_cast<int>(p.size()) - 1);
  const double window = need_m_ + 2.0 * lattice_.longest_edge_m;  // farther apart at a step's start: clear in it
  std::vector<int> order(static_cast<std::size_t>(n));
  int count = 0;
  for (int t = 0; t <= horizon; ++t) {
    const auto at = [&](int i, int time) { return lattice_.position[vertex_at(paths[i], time)]; };
    for (int i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const double xa = at(a, t).x(), xb = at(b, t).x();
      return xa != xb ? xa < xb : a < b;
    });
    std::optional<PathConflict> best;
    const auto better = [&](const PathConflict& c) {
      return !best || std::make_pair(c.a.agent, c.b.agent) < std::make_pair(best->a.agent, best->b.agent);
    };
    for (int s = 0; s < n; ++s) {
      const int i = order[s];
      const Vec3 a0 = at(i, t), a1 = at(i, t + 1);
      for (int r = s + 1; r < n && at(order[r], t).x() - a0.x() < window; ++r) {
        const int j = order[r];
        const Vec3 b0 = at(j, t), b1 = at(j, t + 1);
        if ((a0 - b0).norm() >= window) continue;
        PathConflict c;
        const int lo = std::min(i, j), hi = std::max(i, j);
        if ((a0 - b0).norm() < need_m_) {
          c = {{lo, vertex_at(paths[lo], t), -1, t}, {hi, vertex_at(paths[hi], t), -1, t}};
        } else if (t < horizon && (a1 - b1).norm() >= need_m_ && moves_conflict(a0, a1, b0, b1)) {
          c = {{lo, vertex_at(paths[lo], t), vertex_at(paths[lo], t + 1), t},
               {hi, vertex_at(paths[hi], t), vertex_at(paths[hi], t + 1), t}};
        } else {
          continue;
        }
        ++count;
        if (better(c)) best = c;
      }
    }
    if (first && best) {
      *out = *best;
      return count;
    }
  }
  return count;
}

std::optional<PathConflict> LatticeAgents::first_conflict(const std::vector<SpaceTimePath>& paths) const {
  PathConflict c;
  if (scan(paths, true, &c) == 0) return std::nullopt;
  return c;
}

int LatticeAgents::count_conflicts(const std::vector<SpaceTimePath>& paths) const {
  return scan(paths, false, nullptr);
}

}  // namespace uavplan
