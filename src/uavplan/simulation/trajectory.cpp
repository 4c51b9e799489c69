#include "uavplan/simulation/trajectory.h"
#include <Eigen/Geometry>

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
    const int pieces = max_dt_s > 0.0 ? std::max(1, static_cast<int>(std::ceil(dur / max_dt_s - 1e-9))) : 1;
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
  const double dur = 2.0 * len / std::max(v0 + v1, 1e-9), acc = (v1 - v0) / dur;
  for (double t = sample_s; t < dur - 1e-9; t += sample_s)
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

Vec3 position_at(const Trajectory& tr, double t) {
  if (tr.empty()) return Vec3::Zero();
  if (t <= tr.front().t_s) return tr.front().p;
  if (t >= tr.back().t_s) return tr.back().p;
  const auto it =
      std::upper_bound(tr.begin(), tr.end(), t, [](double x, const TrajectorySample& s) { return x < s.t_s; });
  const TrajectorySample& b = *it;
  const TrajectorySample& a = *(it - 1);
  const double span = b.t_s - a.t_s;
  if (span <= 0.0) return b.p;
  return a.p + (t - a.t_s) / span * (b.p - a.p);
}

namespace {

// position_at for non-decreasing times, walking forward instead of searching.
class Cursor {
 public:
  explicit Cursor(const Trajectory& tr) : tr_(&tr) {}
  Vec3 at(double t) {
    const Trajectory& tr = *tr_;
    if (t <= tr.front().t_s) return tr.front().p;
    if (t >= tr.back().t_s) return tr.back().p;
    while (tr[next_].t_s <= t) ++next_;  // the first sample after t, as position_at's upper_bound
    const TrajectorySample& b = tr[next_];
    const TrajectorySample& a = tr[next_ - 1];
    const double span = b.t_s - a.t_s;
    if (span <= 0.0) return b.p;
    return a.p + (t - a.t_s) / span * (b.p - a.p);
  }

 private:
  const Trajectory* tr_;
  std::size_t next_ = 1;
};

}  // namespace

Encounter closest_approach(const Trajectory& a, const Trajectory& b, double t_max_s) {
  Encounter e;
  if (a.empty() || b.empty()) return e;
  Cursor ca(a), cb(b);
  auto consider = [&](double t0, const Vec3& pa0, const Vec3& pb0, double t1, const Vec3& pa1, const Vec3& pb1) {
    double u = 0.0;
    const double dist = point_segment_distance(Vec3::Zero(), pa0 - pb0, pa1 - pb1, &u);
    if (dist < e.distance_m) {
      e.distance_m = dist;
      e.t_s = t0 + u * (t1 - t0);
      e.where = pa0 + u * (pa1 - pa0);
    }
  };
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
      consider(t, pa, pb, t, pa, pb);
    else
      consider(t_prev, pa_prev, pb_prev, t, pa, pb);
    first = false;
    t_prev = t;
    pa_prev = pa;
    pb_prev = pb;
  }
  if (first) {  // every sample after t_max_s: where both are at t_max_s
    const Vec3 pa = ca.at(t_max_s), pb = cb.at(t_max_s);
    consider(t_max_s, pa, pb, t_max_s, pa, pb);
  }
  return e;
}

SweptBoxes::SweptBoxes(std::span<const Trajectory* const> trs, int slices) : slices_(std::max(1, slices)) {
  double t0 = World::kInf, t1 = -World::kInf;
  for (const Trajectory* tr : trs)
    if (!tr->empty()) t0 = std::min(t0, tr->front().t_s), t1 = std::max(t1, tr->back().t_s);
  const double w = t1 > t0 ? (t1 - t0) / slices_ : 1.0;
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
