#include "uavplan/planning/search/directional_astar.h"
#include "uavplan/core/text.h"

#include <cstdio>

#include "uavplan/planning/grid_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "uavplan/core/geometry.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

DirectionalAStarOptions DirectionalAStarOptions::from_params(const Params& params) {
  ParamReader r(params, "directional_astar");
  DirectionalAStarOptions o;
  o.cell_m = r.number("cell_m", o.cell_m, 0.0, 1e9);
  o.step_cells = r.number("step_cells", o.step_cells, 0.0, 100.0);
  if (o.step_cells > 0.0 && o.step_cells < 0.5)
    throw std::invalid_argument("planner.params.step_cells: must be 0 (derived) or at least 0.5");
  o.directions = r.integer("directions", o.directions, 1, 64);
  o.max_yaw_rad = deg_to_rad(r.number("max_yaw_deg", rad_to_deg(o.max_yaw_rad), 0.0, 180.0));
  o.max_pitch_rad = deg_to_rad(r.number("max_pitch_deg", rad_to_deg(o.max_pitch_rad), 0.0, 90.0));
  o.max_expansions = r.integer("max_expansions", static_cast<int>(o.max_expansions), 1, 1'000'000'000);
  o.target_points = static_cast<std::int64_t>(r.number("target_points", static_cast<double>(o.target_points), 1, 1e9));
  o.step_cells_max = r.number("step_cells_max", o.step_cells_max, 0.5, 100.0);
  o.min_turn_radius_m = r.number("min_turn_radius_m", o.min_turn_radius_m, 0.0, 1e9);
  o.heuristic_weight = r.number("heuristic_weight", o.heuristic_weight, 1.0, 10.0);
  o.climb_bound = r.boolean("climb_bound", o.climb_bound);
  o.relaxed_heuristic = r.boolean("relaxed_heuristic", o.relaxed_heuristic);
  o.incumbent_weight = r.number("incumbent_weight", o.incumbent_weight, 1.0, 10.0);
  r.finish();
  return o;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kDefaultYaw_rad = kPi / 3;    // P4's psi_max when the UAV states none
constexpr double kDefaultPitch_rad = kPi / 6;  // P4's phi_max

struct Lattice {
  Vec3 origin;
  double cell;
  int n[3];
  std::int64_t size() const { return static_cast<std::int64_t>(n[0]) * n[1] * n[2]; }
  std::uint32_t index(int i, int j, int k) const {
    return static_cast<std::uint32_t>((static_cast<std::int64_t>(k) * n[1] + j) * n[0] + i);
  }
  double inv_n0 = 1.0, inv_n01 = 1.0;  // 1 / n[0] and 1 / (n[0] n[1]), for coords()

  // The coordinates of a lattice index, dividing by multiplying with a reciprocal and correcting
  // the quotient by one where rounding left it off (exact for any 32-bit index): the search
  // decodes two indices per expansion, and integer division is slow.
  static std::uint32_t quotient(std::uint32_t a, std::uint32_t d, double inv_d) {
    auto q = static_cast<std::uint32_t>(static_cast<double>(a) * inv_d);
    if (std::uint64_t{q} * d > a)
      --q;
    else if ((std::uint64_t{q} + 1) * d <= a)
      ++q;
    return q;
  }
  void coords(std::uint32_t id, int& i, int& j, int& k) const {
    const auto n0 = static_cast<std::uint32_t>(n[0]), n01 = n0 * static_cast<std::uint32_t>(n[1]);
    const std::uint32_t r = quotient(id, n0, inv_n0), kk = quotient(id, n01, inv_n01);
    i = static_cast<int>(id - r * n0);
    j = static_cast<int>(r - kk * static_cast<std::uint32_t>(n[1]));
    k = static_cast<int>(kk);
  }
  Vec3 at(int i, int j, int k) const {
    return origin + cell * Vec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
  }
  Vec3 point(std::uint32_t id) const {
    int i, j, k;
    coords(id, i, j, k);
    return at(i, j, k);
  }
  // The lattice points at the corners of the lattice cell around p (clamped into the bounds),
  // nearest first: the candidates for P4's "nearest equivalent". No integer division: corner
  // positions come from the cell's own coordinates.
  int corners(const Vec3& p, std::uint32_t ids[8], Vec3 pts[8]) const {
    int lo[3];
    for (int a = 0; a < 3; ++a)
      lo[a] = static_cast<int>(
          std::clamp(std::floor((p[a] - origin[a]) / cell), 0.0, static_cast<double>(std::max(n[a] - 2, 0))));
    double d2[8];
    int k = 0;
    for (int dz = 0; dz <= (n[2] > 1); ++dz)
      for (int dy = 0; dy <= (n[1] > 1); ++dy)
        for (int dx = 0; dx <= (n[0] > 1); ++dx) {
          const Vec3 c = origin + cell * Vec3(lo[0] + dx, lo[1] + dy, lo[2] + dz);
          double dist = (c - p).squaredNorm();
          std::uint32_t id = index(lo[0] + dx, lo[1] + dy, lo[2] + dz);
          int j = k++;
          for (; j > 0 && d2[j - 1] > dist; --j) {  // insertion, nearest first
            d2[j] = d2[j - 1];
            ids[j] = ids[j - 1];
            pts[j] = pts[j - 1];
          }
          d2[j] = dist;
          ids[j] = id;
          pts[j] = c;
        }
    return k;
  }
};

// The lattice of a query: points every `cell` from the bounds' lower corner. A world less than a
// cell high has one level, at the start's height (clamped into the bounds), not on the floor.
Lattice make_lattice(const World& world, const DirectionalQuery& q) {
  const double cell = q.cell_m;
  Lattice l{world.bounds().min, cell, {1, 1, 1}};
  const Vec3 ext = world.bounds().extent();
  for (int a = 0; a < 3; ++a) l.n[a] = 1 + static_cast<int>(std::min(std::floor(ext[a] / cell + 1e-9), 2e6));
  if (l.n[2] == 1) l.origin.z() = std::clamp(q.start.z(), world.bounds().min.z(), world.bounds().max.z());
  l.inv_n0 = 1.0 / l.n[0];
  l.inv_n01 = 1.0 / (static_cast<double>(l.n[0]) * l.n[1]);
  return l;
}

double derived_cell(const World& world, std::int64_t target_points) {
  return cell_for_count_m(world.bounds().extent(), static_cast<double>(target_points));
}

// The turn and climb limits as a cosine and a tangent, checked with dot products: the same
// tests as turn_rad() and pitch_rad() (3-D angle and yaw change within psi_max, |pitch| within
// phi_max). Scale-free, so they hold for offsets in metres or in cells.
struct ConeLimits {
  double cos_turn, tan_pitch;
  ConeLimits(double max_yaw_rad, double max_pitch_rad)
      : cos_turn(std::cos(std::min(max_yaw_rad + kAngleTolerance_rad, kPi))),
        tan_pitch(max_pitch_rad + kAngleTolerance_rad >= kPi / 2 ? 1e300
                                                                 : std::tan(max_pitch_rad + kAngleTolerance_rad)) {}
  explicit ConeLimits(const DirectionalQuery& q) : ConeLimits(q.max_yaw_rad, q.max_pitch_rad) {}
  bool pitch_ok(const Vec3& seg) const { return std::abs(seg.z()) <= tan_pitch * seg.head<2>().norm(); }
  bool turn_ok(const std::optional<Vec3>& from, const Vec3& seg) const {
    if (!from) return true;
    const double n1 = from->norm(), n2 = seg.norm();
    if (n1 <= 0.0 || n2 <= 0.0) return true;
    if (from->dot(seg) < cos_turn * n1 * n2) return false;
    const double h1 = from->head<2>().norm(), h2 = seg.head<2>().norm();
    if (h1 > 1e-9 * n1 && h2 > 1e-9 * n2 && from->head<2>().dot(seg.head<2>()) < cos_turn * h1 * h2) return false;
    return true;
  }
};

// The directions of the cone (P4 eq. 8, psi and phi in their roles): yaw a of my spread over
// [yaw0 - span, yaw0 + span] (the whole circle without a heading), pitch b of mp over
// [-phi_max, phi_max], yaw outermost. Sines and cosines once per yaw and per pitch.
class ConeDirections {
 public:
  static constexpr int kMaxPitches = 64;  // DirectionalQuery::directions is at most this
  ConeDirections(int mp, double max_pitch) : mp_(std::clamp(mp, 1, kMaxPitches)) {
    for (int b = 0; b < mp_; ++b) {
      const double pitch = mp_ == 1 ? 0.0 : -max_pitch + 2.0 * max_pitch * b / (mp_ - 1);
      cos_pitch_[b] = std::cos(pitch);
      sin_pitch_[b] = std::sin(pitch);
    }
  }
  template <class F>
  void for_each(double yaw0, double yaw_span, int my, bool has_heading, F&& f) const {
    for (int a = 0; a < my; ++a) {
      const double yaw = yaw0 + (my == 1 ? 0.0 : -yaw_span + 2.0 * yaw_span * a / (has_heading ? my - 1 : my));
      const double cy = std::cos(yaw), sy = std::sin(yaw);
      for (int b = 0; b < mp_; ++b) f(Vec3(cos_pitch_[b] * cy, cos_pitch_[b] * sy, sin_pitch_[b]));
    }
  }

 private:
  int mp_;
  double cos_pitch_[kMaxPitches], sin_pitch_[kMaxPitches];
};

// The work of two searches of one query in `to`'s counts (a lattice point opened by both is
// counted once by the second: see count_afresh).
void add_counts(DirectionalRoute& to, const DirectionalRoute& from) {
  to.expanded += from.expanded;
  to.generated += from.generated;
  to.opened += from.opened;
  to.cells_opened += from.cells_opened;
  to.dead_zones += from.dead_zones;
  to.relaxed_expanded += from.relaxed_expanded;
  to.open_max = std::max(to.open_max, from.open_max);
}

std::optional<Vec3> start_heading(const DirectionalQuery& q) {
  if (q.start_direction) return q.start_direction;
  if (q.heading_rad) return heading_vector(*q.heading_rad);
  return std::nullopt;
}

std::uint32_t pack_offset(int dx, int dy, int dz) {
  return (static_cast<std::uint32_t>(dx + 512) << 20) | (static_cast<std::uint32_t>(dy + 512) << 10) |
         static_cast<std::uint32_t>(dz + 512);
}

// The general expansion of P4 (any point, the start's heading or none): for each direction of
// the cone, the target L cells away and the nearest lattice point around it that keeps the turn
// and climb limits ("nearest equivalent", P4 sec. 3.1, fig. 3). f(id, point) gets each.
template <class F>
void general_children(const Lattice& lat, const DirectionalQuery& q, const ConeLimits& lim, bool flat, const Vec3& p,
                      const std::optional<Vec3>& heading, F&& f) {
  const int m = std::max(1, q.directions), mp = flat ? 1 : m;
  const double yaw0 =
      heading ? std::atan2(heading->y(), heading->x()) : std::atan2(q.goal.y() - p.y(), q.goal.x() - p.x());
  const double yaw_span = heading ? q.max_yaw_rad : kPi;
  const int my =
      heading
          ? m
          : std::max(m, static_cast<int>(std::ceil(2 * kPi / std::max(2 * q.max_yaw_rad / std::max(m - 1, 1), 1e-3))));
  ConeDirections(mp, q.max_pitch_rad).for_each(yaw0, yaw_span, my, heading.has_value(), [&](const Vec3& dir) {
    const Vec3 target = p + q.step_cells * q.cell_m * dir;
    std::uint32_t cand[8];
    Vec3 cand_pt[8];
    const int nc = lat.corners(target, cand, cand_pt);
    for (int c = 0; c < nc; ++c) {
      const Vec3 seg = cand_pt[c] - p;
      if (seg.norm() < 1e-9 || !lim.turn_ok(heading, seg) || !lim.pitch_ok(seg)) continue;
      f(cand[c], cand_pt[c]);
      break;
    }
  });
}

// One cone (see DirectionalCones): the expansion of the search for a lattice point away from the
// bounds, in cells: the target L cells along each direction, the corners of its lattice cell
// nearest first, the first corner that keeps the limits.
DirectionalCones::Cone build_cone(const DirectionalCones::Key& key, int dx, int dy, int dz) {
  const ConeLimits lim(key.max_yaw_rad, key.max_pitch_rad);
  const std::optional<Vec3> heading = Vec3(dx, dy, dz);
  const double yaw0 = std::atan2(heading->y(), heading->x());
  const int m = key.directions, mp = key.flat ? 1 : m;
  DirectionalCones::Cone c;
  ConeDirections(mp, key.max_pitch_rad).for_each(yaw0, key.max_yaw_rad, m, true, [&](const Vec3& dir) {
    const Vec3 t = key.step_cells * dir;
    const Vec3 lo(std::floor(t.x()), std::floor(t.y()), key.flat ? 0.0 : std::floor(t.z()));
    Vec3 pts[8];
    double d2[8];
    int n = 0;
    for (int cz = 0; cz <= (key.flat ? 0 : 1); ++cz)
      for (int cy = 0; cy <= 1; ++cy)
        for (int cx = 0; cx <= 1; ++cx) {
          const Vec3 corner = lo + Vec3(cx, cy, cz);
          const double dist = (corner - t).squaredNorm();
          int j = n++;
          for (; j > 0 && d2[j - 1] > dist; --j) {  // insertion, nearest first (as Lattice::corners)
            d2[j] = d2[j - 1];
            pts[j] = pts[j - 1];
          }
          d2[j] = dist;
          pts[j] = corner;
        }
    for (int i = 0; i < n; ++i) {
      const Vec3& seg = pts[i];
      if (seg.norm() < 1e-9 || !lim.turn_ok(heading, seg) || !lim.pitch_ok(seg)) continue;
      const DirectionalCones::Child child{
          {static_cast<std::int16_t>(seg.x()), static_cast<std::int16_t>(seg.y()), static_cast<std::int16_t>(seg.z())},
          seg.norm()};
      const bool seen = std::any_of(c.children.begin(), c.children.end(), [&](const DirectionalCones::Child& o) {
        return o.d[0] == child.d[0] && o.d[1] == child.d[1] && o.d[2] == child.d[2];
      });
      if (!seen) {
        c.children.push_back(child);
        c.max_length_cells = std::max(c.max_length_cells, child.length_cells);
      }
      break;
    }
  });
  return c;
}

// What to change when the lattice finds no route within the limits. A move L cells away climbs
// at least one cell: atan(1 / L) above the climb limit means it cannot climb or descend at all.
std::string limits_hint(const DirectionalQuery& q, bool flat) {
  const double least_climb = std::atan(1.0 / q.step_cells);
  if (!flat && least_climb > q.max_pitch_rad + 1e-12) {
    return strf(
        "the lattice's least climb, atan(1 / step_cells) = %.1f deg, is steeper than the climb limit of %.1f deg, "
        "so it cannot change height: give planner.params.step_cells >= %.1f (and a smaller cell_m to keep "
        "its turns tight)",
        rad_to_deg(least_climb), rad_to_deg(q.max_pitch_rad), std::ceil(10.0 / std::tan(q.max_pitch_rad)) / 10.0);
  }
  return strf(
      "a longer planner.params.step_cells (now %.2f) gives finer turns and climbs, a smaller cell_m (now %g m) "
      "more room to turn",
      q.step_cells, q.cell_m);
}

}  // namespace

struct DirectionalCones::Table {
  Key key;
  std::unordered_map<std::uint32_t, Cone> cones;  // by packed heading offset
  std::unordered_set<std::uint32_t> level_kept;   // headings from which no move changes level
};

DirectionalCones::DirectionalCones() = default;
DirectionalCones::~DirectionalCones() = default;

DirectionalCones::Table& DirectionalCones::table(const Key& key) {
  const std::lock_guard lock(mutex_);
  for (const auto& t : tables_)
    if (t->key == key) return *t;
  tables_.push_back(std::make_unique<Table>(Table{key, {}, {}}));
  return *tables_.back();
}

const DirectionalCones::Cone& DirectionalCones::cone(Table& table, int dx, int dy, int dz) {
  const std::lock_guard lock(mutex_);
  return cone_locked(table, dx, dy, dz);
}

const DirectionalCones::Cone& DirectionalCones::cone_locked(Table& table, int dx, int dy, int dz) {
  const std::uint32_t k = pack_offset(dx, dy, dz);
  if (const auto it = table.cones.find(k); it != table.cones.end()) return it->second;
  return table.cones.emplace(k, build_cone(table.key, dx, dy, dz)).first->second;
}

bool DirectionalCones::level_change_reachable(Table& table, const std::vector<std::uint32_t>& headings) {
  const std::lock_guard lock(mutex_);
  std::vector<std::uint32_t> frontier;  // headings whose cones are not yet read
  std::unordered_set<std::uint32_t> seen;
  auto visit = [&](std::uint32_t k) {
    if (!table.level_kept.contains(k) && seen.insert(k).second) frontier.push_back(k);
  };
  for (const std::uint32_t k : headings) visit(k);
  while (!frontier.empty()) {
    const std::uint32_t k = frontier.back();
    frontier.pop_back();
    const int dx = static_cast<int>(k >> 20) - 512, dy = static_cast<int>((k >> 10) & 1023) - 512,
              dz = static_cast<int>(k & 1023) - 512;
    for (const Child& c : cone_locked(table, dx, dy, dz).children) {
      if (c.d[2] != 0) return true;
      visit(pack_offset(c.d[0], c.d[1], c.d[2]));
    }
  }
  // Every heading seen leads only to headings seen or known to keep the level.
  table.level_kept.insert(seen.begin(), seen.end());
  return false;
}

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

// L when the scenario gives none: max(2.5, 2 / psi_max) (lattice directions L cells away are about
// 1 / L rad apart, so a finer turn limit needs a longer step to turn at all), and in 3-D at least
// 1 / tan(phi_max), rounded up to a tenth: the least climb of a move, one cell in L, must keep the
// climb limit, or the search could never change height (15 deg: 3.8 cells).
static double default_step_cells(const World& world, const DirectionalQuery& q) {
  double l = std::max(2.5, 2.0 / q.max_yaw_rad);
  if (make_lattice(world, q).n[2] > 1 && q.max_pitch_rad < kPi / 2 - 1e-9)
    l = std::max(l, std::ceil(10.0 / std::tan(q.max_pitch_rad) - 1e-9) / 10.0);
  return l;
}

DirectionalQuery DirectionalAStarPlanner::query_for(const Problem& pb, const World& world) const {
  const UavSpec& u = pb.uav;
  DirectionalQuery q;
  q.start = u.start;
  q.goal = pb.goal;
  q.heading_rad = u.heading_rad;
  q.cell_m = options_.cell_m > 0.0 ? options_.cell_m : derived_cell(world, options_.target_points);
  q.directions = options_.directions;
  const double uav_yaw = u.max_turn_rad < kPi - 1e-9 ? u.max_turn_rad : kDefaultYaw_rad;
  const double uav_pitch = u.max_climb_rad < kPi / 2 - 1e-9 ? u.max_climb_rad : kDefaultPitch_rad;
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

DirectionalRoute DirectionalSearch::run(const World& world, const DirectionalQuery& q, const StopCondition& stop) {
  if (q.directions > ConeDirections::kMaxPitches) {
    DirectionalRoute r;
    r.message = "directions: at most " + std::to_string(ConeDirections::kMaxPitches);
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
  if (incumbent.stopped) return incumbent;
  DirectionalQuery exact = q;
  // The bound admits the incumbent's own length whatever the order of the sums.
  if (incumbent.found) exact.max_length_m = incumbent.length_m * (1.0 + 1e-9) + 1e-9 * q.cell_m;
  DirectionalRoute r = run_with_bins(world, exact, stop, bins, false);
  add_counts(r, incumbent);
  if (r.found || !incumbent.found) return r;
  r.found = true;
  r.stopped = false;
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
  out.stopped = static_cast<std::int64_t>(out.expanded) <= q.max_expansions;
  out.message = out.stopped
                    ? "stopped before a route was found"
                    : "expansion limit reached (planner.params.max_expansions = " + std::to_string(q.max_expansions) +
                          "; raise it, or give a larger cell_m)";
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
    out.message = "no route within the length bound";
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
  out.found = true;
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
    out.message = "lattice too large; give a larger cell_m";
    return out;
  }
  return Run(*this, world, q, stop, bins, count_afresh).search();
}

void DirectionalAStarPlanner::require_lattice(const World& world, const DirectionalQuery& q, int engines,
                                              const StopCondition& stop) {
  const Vec3 ext = world.bounds().extent();
  double points = 1.0;
  for (int a = 0; a < 3; ++a) points *= 1.0 + std::floor(ext[a] / q.cell_m + 1e-9);
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
    if (!r.found) {
      res.message = r.stopped ? r.message : leg_name(leg, stops.size()) + ": " + r.message;
      res.reason = r.stopped                                                   ? Reason::stopped
                   : r.expanded > static_cast<std::uint64_t>(q.max_expansions) ? Reason::budget
                                                                               : Reason::no_route;
      res.route.waypoints.clear();
      return res;
    }
    res.route.waypoints.insert(res.route.waypoints.end(), r.waypoints.begin() + 1, r.waypoints.end());
  }
  res.status = Status::solved;
  return res;
}

}  // namespace uavplan
