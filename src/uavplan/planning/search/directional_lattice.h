// The lattice and the cones of P4's directional A* (directional_astar.h), shared by its parts:
// the cone tables (directional_cones.cpp), the search (directional_search.cpp) and the planner
// (directional_astar.cpp). Internal to the planner: nothing outside planning/search includes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"
#include "uavplan/planning/grid_budget.h"
#include "uavplan/planning/search/directional_astar.h"

namespace uavplan::directional {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kDefaultYaw_rad = kPi / 3;    // P4's psi_max when the UAV states none
inline constexpr double kDefaultPitch_rad = kPi / 6;  // P4's phi_max

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
inline Lattice make_lattice(const World& world, const DirectionalQuery& q) {
  const double cell = q.cell_m;
  Lattice l{world.bounds().min, cell, {1, 1, 1}};
  const Vec3 ext = world.bounds().extent();
  for (int a = 0; a < 3; ++a)
    l.n[a] = 1 + static_cast<int>(std::min(std::floor(ext[a] / cell + kWholeNumberSlack), 2e6));
  if (l.n[2] == 1) l.origin.z() = std::clamp(q.start.z(), world.bounds().min.z(), world.bounds().max.z());
  l.inv_n0 = 1.0 / l.n[0];
  l.inv_n01 = 1.0 / (static_cast<double>(l.n[0]) * l.n[1]);
  return l;
}

inline double derived_cell(const World& world, std::int64_t target_points) {
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
inline void add_counts(DirectionalRoute& to, const DirectionalRoute& from) {
  to.expanded += from.expanded;
  to.generated += from.generated;
  to.opened += from.opened;
  to.cells_opened += from.cells_opened;
  to.dead_zones += from.dead_zones;
  to.relaxed_expanded += from.relaxed_expanded;
  to.open_max = std::max(to.open_max, from.open_max);
}

inline std::optional<Vec3> start_heading(const DirectionalQuery& q) {
  if (q.start_direction) return q.start_direction;
  if (q.heading_rad) return heading_vector(*q.heading_rad);
  return std::nullopt;
}

inline std::uint32_t pack_offset(int dx, int dy, int dz) {
  return (static_cast<std::uint32_t>(dx + 512) << 20) | (static_cast<std::uint32_t>(dy + 512) << 10) |
         static_cast<std::uint32_t>(dz + 512);
}

// The general expansion of P4 (any point, the start's heading or none): for each direction of
// the cone, the target L cells away and the nearest lattice point around it that keeps the turn
// and climb limits ("nearest equivalent", P4 sec. 3.1, fig. 3). f(id, point) gets each.
template <class F>
inline void general_children(const Lattice& lat, const DirectionalQuery& q, const ConeLimits& lim, bool flat,
                             const Vec3& p, const std::optional<Vec3>& heading, F&& f) {
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
      if (seg.norm() < kSamePoint_m || !lim.turn_ok(heading, seg) || !lim.pitch_ok(seg)) continue;
      f(cand[c], cand_pt[c]);
      break;
    }
  });
}

// What to change when the lattice finds no route within the limits. A move L cells away climbs
// at least one cell: atan(1 / L) above the climb limit means it cannot climb or descend at all.
inline std::string limits_hint(const DirectionalQuery& q, bool flat) {
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

}  // namespace uavplan::directional
