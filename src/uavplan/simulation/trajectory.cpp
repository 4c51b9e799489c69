#include "uavplan/simulation/trajectory.h"
#include <Eigen/Geometry>
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

#include "uavplan/core/geometry.h"

namespace uavplan {

Trajectory time_route(std::span<const Vec3> pts, double speed_mps, double depart_s, double max_dt_s) {
  Trajectory tr;
  if (pts.empty()) return tr;
  tr.push_back({0.0, pts[0]});
  double t = std::max(0.0, depart_s);
  if (t > 0.0) tr.push_back({t, pts[0]});
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double len = (pts[i] - pts[i - 1]).norm();
    if (len <= 0.0) continue;
    const double dur = len / speed_mps;
    const int pieces =
        max_dt_s > 0.0 ? std::max(1, static_cast<int>(std::ceil(dur / max_dt_s - kWholeNumberSlack))) : 1;
    for (int k = 1; k <= pieces; ++k) {
      const double f = static_cast<double>(k) / pieces;
      tr.push_back({t + f * dur, k == pieces ? pts[i] : Vec3(pts[i - 1] + f * (pts[i] - pts[i - 1]))});
    }
    t += dur;
  }
  return tr;
}

void append_straight_run(Trajectory& tr, const Vec3& to, double v0, double v1, double sample_s) {
  const Vec3 from = tr.back().p;
  const double len = (to - from).norm(), t0 = tr.back().t_s;
  if (len <= 0.0) return;
  const double dur = 2.0 * len / std::max(v0 + v1, kTinyDivisor), acc = (v1 - v0) / dur;
  for (double t = sample_s; t < dur - kSameTime_s; t += sample_s)
    tr.push_back({t0 + t, from + (v0 * t + 0.5 * acc * t * t) / len * (to - from)});
  tr.push_back({t0 + dur, to});
}

bool passes_within(const Trajectory& tr, const Vec3& p, double tol_m, TrackProgress& at) {
  if (tr.size() == 1) return (tr[0].p - p).norm() <= tol_m;
  for (; at.segment + 1 < tr.size(); ++at.segment, at.fraction = 0.0) {
    const Vec3 a = tr[at.segment].p + at.fraction * (tr[at.segment + 1].p - tr[at.segment].p);
    double t = 0.0;
    if (point_segment_distance(p, a, tr[at.segment + 1].p, &t) <= tol_m) {
      at.fraction += t * (1.0 - at.fraction);
      return true;
    }
  }
  return false;
}

namespace {

// The point at t on the piece from sample a to sample b (b's point where they share a time).
Vec3 on_piece(const TrajectorySample& a, const TrajectorySample& b, double t) {
  const double span = b.t_s - a.t_s;
  return span <= 0.0 ? b.p : Vec3(a.p + (t - a.t_s) / span * (b.p - a.p));
}

// position_at(tr, t) where `next` is the first sample after t (upper_bound), no search.
Vec3 between(const Trajectory& tr, std::size_t next, double t) {
  if (next == 0) return tr.front().p;
  if (next == tr.size()) return tr.back().p;
  return on_piece(tr[next - 1], tr[next], t);
}

// position_at for non-decreasing times, walking forward instead of searching.
class Cursor {
 public:
  explicit Cursor(const Trajectory& tr) : tr_(&tr) {}
  Vec3 at(double t) {
    const Trajectory& tr = *tr_;
    if (t <= tr.front().t_s) return tr.front().p;
    if (t >= tr.back().t_s) return tr.back().p;
    while (tr[next_].t_s <= t) ++next_;  // the first sample after t, as position_at's upper_bound
    return on_piece(tr[next_ - 1], tr[next_], t);
  }

 private:
  const Trajectory* tr_;
  std::size_t next_ = 1;
};

// Two UAVs flying straight from (pa0, pb0) at t0 to (pa1, pb1) at t1: their offset moves along a
// segment, and its point nearest the origin is their closest approach on that piece; kept in `e`
// when nearer than what it holds.
void nearer_on_piece(Encounter& e, double t0, const Vec3& pa0, const Vec3& pb0, double t1, const Vec3& pa1,
                     const Vec3& pb1) {
  double u = 0.0;
  const double dist = point_segment_distance(Vec3::Zero(), pa0 - pb0, pa1 - pb1, &u);
  if (dist < e.distance_m) {
    e.distance_m = dist;
    e.t_s = t0 + u * (t1 - t0);
    e.where = pa0 + u * (pa1 - pa0);
  }
}

}  // namespace

Vec3 position_at(const Trajectory& tr, double t) {
  if (tr.empty()) return Vec3::Zero();
  if (t <= tr.front().t_s) return tr.front().p;
  if (t >= tr.back().t_s) return tr.back().p;
  const auto it =
      std::upper_bound(tr.begin(), tr.end(), t, [](double x, const TrajectorySample& s) { return x < s.t_s; });
  return on_piece(*(it - 1), *it, t);
}

Encounter closest_approach_between(const Trajectory& a, const Trajectory& b, double t_from_s, double t_to_s) {
  Encounter e;
  if (a.empty() || b.empty() || !(t_from_s <= t_to_s)) return e;
  auto first_after = [&](const Trajectory& tr) {
    return static_cast<std::size_t>(std::upper_bound(tr.begin(), tr.end(), t_from_s,
                                                     [](double x, const TrajectorySample& s) { return x < s.t_s; }) -
                                    tr.begin());
  };
  std::size_t i = first_after(a), j = first_after(b);
  double t_prev = t_from_s;
  Vec3 pa_prev = position_at(a, t_from_s), pb_prev = position_at(b, t_from_s);
  auto consider = [&](double t, const Vec3& pa, const Vec3& pb) {
    nearer_on_piece(e, t_prev, pa_prev, pb_prev, t, pa, pb);
    t_prev = t, pa_prev = pa, pb_prev = pb;
  };
  consider(t_from_s, pa_prev, pb_prev);
  while (i < a.size() || j < b.size()) {
    const double t = i == a.size() ? b[j].t_s : j == b.size() ? a[i].t_s : std::min(a[i].t_s, b[j].t_s);
    if (t >= t_to_s) break;
    while (i < a.size() && a[i].t_s == t) ++i;
    while (j < b.size() && b[j].t_s == t) ++j;
    consider(t, between(a, i, t), between(b, j, t));
  }
  consider(t_to_s, position_at(a, t_to_s), position_at(b, t_to_s));
  return e;
}

Encounter closest_approach(const Trajectory& a, const Trajectory& b, double t_max_s) {
  Encounter e;
  if (a.empty() || b.empty()) return e;
  Cursor ca(a), cb(b);
  // The merged sample times in order (each once), cut at t_max_s.
  std::size_t i = 0, j = 0;
  bool first = true, cut = false;
  double t_prev = 0.0;
  Vec3 pa_prev, pb_prev;
  while (!cut && (i < a.size() || j < b.size())) {
    double t = i == a.size() ? b[j].t_s : j == b.size() ? a[i].t_s : std::min(a[i].t_s, b[j].t_s);
    while (i < a.size() && a[i].t_s == t) ++i;
    while (j < b.size() && b[j].t_s == t) ++j;
    if (t > t_max_s) {
      if (first) break;
      t = t_max_s;
      cut = true;
    }
    const Vec3 pa = ca.at(t), pb = cb.at(t);
    if (first)
      nearer_on_piece(e, t, pa, pb, t, pa, pb);
    else
      nearer_on_piece(e, t_prev, pa_prev, pb_prev, t, pa, pb);
    first = false;
    t_prev = t;
    pa_prev = pa;
    pb_prev = pb;
  }
  if (first) {  // every sample after t_max_s: where both are at t_max_s
    const Vec3 pa = ca.at(t_max_s), pb = cb.at(t_max_s);
    nearer_on_piece(e, t_max_s, pa, pb, t_max_s, pa, pb);
  }
  return e;
}

SweptBoxes::SweptBoxes(std::span<const Trajectory* const> trs, int slices) : slices_(std::max(1, slices)) {
  double t0 = World::kInf, t1 = -World::kInf;
  for (const Trajectory* tr : trs)
    if (!tr->empty()) t0 = std::min(t0, tr->front().t_s), t1 = std::max(t1, tr->back().t_s);
  const double w = t1 > t0 ? (t1 - t0) / slices_ : 1.0;
  t0_s_ = t0, width_s_ = w, t1_s_ = t1;
  boxes_.resize(trs.size() * static_cast<std::size_t>(slices_));
  for (std::size_t n = 0; n < trs.size(); ++n) {
    const Trajectory& tr = *trs[n];
    if (tr.empty()) continue;
    Aabb* box = &boxes_[n * static_cast<std::size_t>(slices_)];
    Cursor c(tr);
    std::size_t k = 0;
    for (int s = 0; s < slices_; ++s) {
      // Slice s: its two ends and every sample between them (held positions outside the samples).
      const double a = t0 + s * w, b = s + 1 == slices_ ? t1 : t0 + (s + 1) * w;
      box[s].extend(c.at(a));
      while (k < tr.size() && tr[k].t_s <= b) {
        if (tr[k].t_s >= a) box[s].extend(tr[k].p);
        ++k;
      }
      box[s].extend(c.at(b));
    }
  }
}

double SweptBoxes::lower_bound_m(std::size_t i, std::size_t j) const {
  const Aabb* a = &boxes_[i * static_cast<std::size_t>(slices_)];
  const Aabb* b = &boxes_[j * static_cast<std::size_t>(slices_)];
  double best = World::kInf;
  for (int s = 0; s < slices_; ++s) {
    if (a[s].empty() || b[s].empty()) continue;
    const Vec3 gap = (a[s].min - b[s].max).cwiseMax(b[s].min - a[s].max).cwiseMax(Vec3::Zero());
    best = std::min(best, gap.squaredNorm());
  }
  return std::sqrt(best);
}

std::vector<SweptBoxes::NearPair> SweptBoxes::pairs_within(double reach_m) const {
  const std::size_t n = slices_ > 0 ? boxes_.size() / static_cast<std::size_t>(slices_) : 0;
  std::vector<std::uint64_t> keys;  // i << 32 | j, every slice's near pairs
  std::vector<std::uint32_t> order;
  const double reach2 = reach_m * reach_m;
  for (int s = 0; s < slices_; ++s) {
    auto box = [&](std::uint32_t k) -> const Aabb& { return boxes_[k * static_cast<std::size_t>(slices_) + s]; };
    order.clear();
    for (std::uint32_t k = 0; k < n; ++k)
      if (!box(k).empty()) order.push_back(k);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return box(a).min.x() < box(b).min.x() || (box(a).min.x() == box(b).min.x() && a < b);
    });
    for (std::size_t x = 0; x < order.size(); ++x) {
      const Aabb& a = box(order[x]);
      for (std::size_t y = x + 1; y < order.size() && box(order[y]).min.x() - a.max.x() < reach_m; ++y) {
        const Aabb& b = box(order[y]);
        const Vec3 gap = (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(Vec3::Zero());
        if (gap.squaredNorm() >= reach2) continue;
        const std::uint32_t i = std::min(order[x], order[y]), j = std::max(order[x], order[y]);
        keys.push_back(std::uint64_t{i} << 32 | j);
      }
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<NearPair> out;
  out.reserve(keys.size());
  for (const std::uint64_t k : keys) {
    const auto i = static_cast<std::uint32_t>(k >> 32), j = static_cast<std::uint32_t>(k & 0xffffffffu);
    out.push_back({i, j, lower_bound_m(i, j)});
  }
  return out;
}

std::vector<std::pair<double, double>> SweptBoxes::near_spans(std::size_t i, std::size_t j, double below_m) const {
  const Aabb* a = &boxes_[i * static_cast<std::size_t>(slices_)];
  const Aabb* b = &boxes_[j * static_cast<std::size_t>(slices_)];
  std::vector<std::pair<double, double>> out;
  for (int s = 0; s < slices_; ++s) {
    if (a[s].empty() || b[s].empty()) continue;
    const Vec3 gap = (a[s].min - b[s].max).cwiseMax(b[s].min - a[s].max).cwiseMax(Vec3::Zero());
    if (gap.norm() >= below_m) continue;
    const double from = t0_s_ + s * width_s_, to = s + 1 == slices_ ? t1_s_ : t0_s_ + (s + 1) * width_s_;
    if (!out.empty() && out.back().second == from)
      out.back().second = to;
    else
      out.emplace_back(from, to);
  }
  return out;
}

Encounter SweptBoxes::closest_below(std::span<const Trajectory* const> trs, std::size_t i, std::size_t j,
                                    double below_m) const {
  Encounter e;
  // Before the common span and after it every trajectory holds its first and last position,
  // as at the span's ends.
  for (const auto& [from, to] : near_spans(i, j, below_m)) {
    const Encounter here = closest_approach_between(*trs[i], *trs[j], from, to);
    if (here.distance_m < e.distance_m) e = here;
  }
  return e;
}

double SweptBoxes::extent_m() const {
  Aabb all;
  for (const Aabb& b : boxes_)
    if (!b.empty()) all.extend(b);
  return all.empty() ? 0.0 : all.extent().norm();
}

Encounter closest_moving_approach(const World& world, const Trajectory& tr, int* index_out) {
  Encounter e;
  if (world.moving().empty() || tr.empty()) return e;
  auto consider = [&](const TrajectorySample& s0, const TrajectorySample& s1) {
    int idx = -1;
    const double gap = world.moving_clearance(s0.p, s0.t_s, s1.p, s1.t_s, &idx);
    if (gap < e.distance_m) {
      e.distance_m = gap;
      e.t_s = s0.t_s;
      e.where = s0.p;
      if (index_out) *index_out = idx;
    }
  };
  consider(tr.front(), tr.front());
  for (std::size_t i = 1; i < tr.size(); ++i) consider(tr[i - 1], tr[i]);
  // After arrival the UAV stays at its last position while obstacles keep moving: check until
  // every obstacle has passed (a constant velocity: its closest approach to the point; a path:
  // its last row, after which it stays).
  const TrajectorySample& last = tr.back();
  double t_far = last.t_s;
  for (const auto& m : world.moving()) {
    if (!m.path.empty()) {
      t_far = std::max(t_far, m.path.back().t_s);
      continue;
    }
    const double v2 = m.velocity_mps.squaredNorm();
    if (v2 > 0.0) t_far = std::max(t_far, (last.p - m.position).dot(m.velocity_mps) / v2);
  }
  if (t_far > last.t_s) consider(last, {t_far, last.p});
  return e;
}

std::vector<Vec3> trajectory_corners(const Trajectory& tr) {
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    if (!out.empty() && tr[i].p == out.back()) continue;
    if (out.size() >= 2) {
      const Vec3 a = out[out.size() - 1] - out[out.size() - 2], b = tr[i].p - out.back();
      if (a.cross(b).norm() <= 1e-12 * a.norm() * b.norm() && a.dot(b) > 0.0) out.pop_back();
    }
    out.push_back(tr[i].p);
  }
  return out;
}

}  // namespace uavplan
