#include "uavplan/coordination/group/group_planner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>

#include "uavplan/core/geometry.h"
#include "uavplan/core/units.h"
#include "uavplan/planning/field/field_guide.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

Trajectory frames_to_trajectory(const std::vector<Vec3>& frames, double frame_s) {
  Trajectory tr;
  for (std::size_t k = 0; k < frames.size(); ++k) tr.push_back({static_cast<double>(k) * frame_s, frames[k]});
  return tr;
}

namespace {

// Position at frame k (held at the last one afterwards).
const Vec3& at(const std::vector<Vec3>& f, std::size_t k) { return f[std::min(k, f.size() - 1)]; }

// Why UAV i cannot fly at all, else empty: its start or goal too near an obstacle (or above
// the ceiling), or its goal or start closer than the separation to an earlier UAV's.
std::string infeasible(const Scenario& sc, std::size_t i) {
  const UavSpec& u = sc.uavs[i];
  const SegmentRule rule(sc.world, u);
  if (!rule.point_ok(u.start)) return "start is closer to an obstacle than the UAV radius, or above the ceiling";
  if (!rule.point_ok(*u.goal)) return "goal is closer to an obstacle than the UAV radius, or above the ceiling";
  for (std::size_t j = 0; j < i; ++j) {
    const UavSpec& v = sc.uavs[j];
    const double need = std::max(sc.mission.separation_m, u.radius_m + v.radius_m);
    if (v.goal && (*v.goal - *u.goal).norm() < need) return "goal is closer than the separation to " + v.id + "'s goal";
    if ((v.start - u.start).norm() < need) return "start is closer than the separation to " + v.id + "'s start";
  }
  return {};
}

// Points bucketed by a grid of `cell` metres (sorted by cell): near(p) visits every point in
// the cells around p's, so every point within `cell` of p among others (p within a cell of
// the points' bounding box). The cell grows when the points span more than 2^20 cells, so the
// packed keys never overflow.
class CellIndex {
 public:
  void build(std::span<const Vec3> points, double cell) {
    Aabb box;
    for (const Vec3& p : points) box.extend(p);
    origin_ = points.empty() ? Vec3::Zero() : box.min;
    cell_ = points.empty() ? cell : std::max(cell, box.extent().maxCoeff() / (1 << 20));
    entries_.resize(points.size());
    std::int64_t k_min = 0, k_max = 0;
    for (std::size_t u = 0; u < points.size(); ++u) {
      const Coords c = coords(points[u]);
      entries_[u] = {key(c[0], c[1], c[2]), static_cast<std::uint32_t>(u)};
      k_min = u == 0 ? c[2] : std::min(k_min, c[2]);
      k_max = u == 0 ? c[2] : std::max(k_max, c[2]);
    }
    flat_ = k_min == k_max;
    std::sort(entries_.begin(), entries_.end());
  }
  // f(index) for the points in the 27 cells around p's (9 when all points share one layer).
  template <class F>
  void near(const Vec3& p, F&& f) const {
    const Coords c = coords(p);
    for (int dk = flat_ ? 0 : -1; dk <= (flat_ ? 0 : 1); ++dk)
      for (int dj = -1; dj <= 1; ++dj) {
        // The three cells of a row are consecutive keys: one search.
        const std::int64_t first = key(c[0] - 1, c[1] + dj, c[2] + dk);
        for (auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{first, 0});
             it != entries_.end() && it->key <= first + 2; ++it)
          f(it->index);
      }
  }

 private:
  using Coords = std::array<std::int64_t, 3>;
  struct Entry {
    std::int64_t key;
    std::uint32_t index;
    bool operator<(const Entry& o) const { return key < o.key || (key == o.key && index < o.index); }
  };
  Coords coords(const Vec3& p) const {
    Coords c;
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) / cell_)), -2,
                                      (1 << 20) + 2) +
             4;
    return c;
  }
  static std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) { return (k << 42) + (j << 21) + i; }

  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1.0;
  bool flat_ = true;
  std::vector<Entry> entries_;
};

// Per UAV and frame of its own raw path, the others within `reach` of it at that frame
// (positions held after a path's end).
class FrameNeighbours {
 public:
  FrameNeighbours(const std::vector<GroupUav>& uavs, double reach) : peers_(uavs.size()), first_(uavs.size()) {
    const std::size_t n = uavs.size();
    std::size_t frames = 0;
    for (const GroupUav& g : uavs) frames = std::max(frames, g.raw.size());
    std::vector<Vec3> pos(n);
    CellIndex index;
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t u = 0; u < n; ++u) pos[u] = at(uavs[u].raw, f);
      index.build(pos, reach);
      for (std::size_t u = 0; u < n; ++u) {
        if (f >= uavs[u].raw.size()) continue;
        first_[u].push_back(static_cast<std::uint32_t>(peers_[u].size()));
        index.near(pos[u], [&](std::uint32_t v) {
          if (v != u && (pos[u] - pos[v]).norm() < reach) peers_[u].push_back(v);
        });
      }
    }
    for (std::size_t u = 0; u < n; ++u) first_[u].push_back(static_cast<std::uint32_t>(peers_[u].size()));
  }

  std::span<const std::uint32_t> at_frame(std::size_t u, std::size_t f) const {
    return {peers_[u].data() + first_[u][f], peers_[u].data() + first_[u][f + 1]};
  }

 private:
  std::vector<std::vector<std::uint32_t>> peers_;
  std::vector<std::vector<std::uint32_t>> first_;  // per frame, where its peers begin
};

}  // namespace

GroupResult plan_group(const Scenario& sc, const ApfOptions& options, const StopCondition& stop) {
  GroupResult res;
  const std::size_t n = sc.uavs.size();
  ApfOptions base = options;
  base.separation_m = sc.mission.separation_m;
  // One step and one frame time for the whole group: the smallest derived step, flown by the
  // slowest UAV in one frame.
  std::vector<ApfOptions> resolved;
  double step = 1e300, slowest = 1e300;
  for (const UavSpec& u : sc.uavs) {
    resolved.push_back(apf_resolved(base, u, sc.world));
    step = std::min(step, resolved.back().step_m);
    slowest = std::min(slowest, u.speed.cruise_mps);
  }
  res.step_m = step;
  res.frame_s = step / slowest;
  std::vector<std::unique_ptr<PotentialField>> fields;
  for (std::size_t i = 0; i < n; ++i) {
    resolved[i].step_m = step;
    resolved[i] = apf_resolved(resolved[i], sc.uavs[i], sc.world);
    fields.push_back(std::make_unique<PotentialField>(sc.world, sc.uavs[i], resolved[i]));
  }
  std::vector<Vec3> cur(n), prev(n);
  std::vector<char> done(n, 0);
  std::vector<FieldFlight> flights;
  double longest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    GroupUav g;
    g.id = sc.uavs[i].id;
    cur[i] = sc.uavs[i].start;
    g.raw.push_back(cur[i]);
    const Vec3 goal = sc.uavs[i].goal.value_or(cur[i]);
    flights.emplace_back(*fields[i], cur[i], goal, -1);  // stalls in a crowd pass: the frame budget bounds them
    if (!sc.uavs[i].goal) {
      g.message = "no goal given";
      done[i] = 1;
    } else if (const std::string why = infeasible(sc, i); !why.empty()) {
      g.message = why;
      done[i] = 1;
    } else if (goal == cur[i]) {
      g.reached = true;
      done[i] = 1;
    } else {
      longest = std::max(longest, (goal - cur[i]).norm());
    }
    res.uavs.push_back(std::move(g));
  }
  // Escape routes (FieldGuide): one grid per distinct body, built at the first stall; UAVs
  // that are done (arrived or failed) never move again, so they are the routes' keep-outs.
  std::vector<std::pair<std::size_t, std::unique_ptr<FieldGuide>>> guides;
  auto guide_for = [&](std::size_t i) -> FieldGuide& {
    const UavSpec& u = sc.uavs[i];
    for (auto& [j, g] : guides) {
      const UavSpec& v = sc.uavs[j];
      if (v.radius_m == u.radius_m && v.max_climb_rad == u.max_climb_rad && v.ceiling_m == u.ceiling_m) return *g;
    }
    guides.emplace_back(i, std::make_unique<FieldGuide>(sc.world, u, step, 2'000'000, stop));
    return *guides.back().second;
  };
  std::vector<KeepOut> keep_out;
  const int max_frames = options.max_frames > 0 ? options.max_frames : static_cast<int>(4.0 * longest / step) + 500;
  std::vector<PeerMotion> peers;
  // Peers near enough to matter: within reach + step (each UAV's own reach, below); the index
  // holds the frame's starting positions and a UAV moves at most a step within the frame.
  double max_radius = 0.0, max_reach = 0.0;
  for (const UavSpec& u : sc.uavs) max_radius = std::max(max_radius, u.radius_m);
  for (const ApfOptions& o : resolved)
    max_reach = std::max(max_reach, o.r_rep_m + base.separation_m + 2 * step + 2 * max_radius);
  CellIndex index;
  // The keep-outs' version for the escape routes: they change when a UAV is done.
  std::uint64_t done_count = static_cast<std::uint64_t>(std::count(done.begin(), done.end(), 1));
  // The escape route of the UAV moving now (`moving`), around the UAVs that are done.
  std::size_t moving = 0;
  const FieldFlight::Guide guide = [&](const Vec3& from, const Vec3& to) {
    keep_out.clear();
    for (std::size_t j = 0; j < n; ++j)
      if (j != moving && done[j])
        keep_out.push_back(
            {cur[j], std::max(base.separation_m, sc.uavs[moving].radius_m + sc.uavs[j].radius_m) + kPlanningMargin_m});
    return guide_for(moving).route(from, to, keep_out);
  };
  int frame = 0;
  for (; frame < max_frames && done_count < n && !stop.should_stop(frame); ++frame) {
    prev = cur;
    index.build(prev, max_reach + 3 * step);
    for (std::size_t i = 0; i < n; ++i) {
      if (done[i]) continue;
      const UavSpec& u = sc.uavs[i];
      // Earlier UAVs with this frame's motion, later ones where they are.
      const double reach = resolved[i].r_rep_m + base.separation_m + 2 * step + u.radius_m + max_radius;
      peers.clear();
      index.near(cur[i], [&](std::uint32_t j) {
        if (j == i || (cur[j] - cur[i]).norm() > reach + step) return;
        peers.push_back({j < i ? prev[j] : cur[j], cur[j], sc.uavs[j].radius_m});
      });
      moving = i;
      cur[i] = flights[i].advance(peers, guide, done_count);
      if (flights[i].failed()) {
        res.uavs[i].message = flights[i].message() + " at frame " + std::to_string(frame);
        done[i] = 1;
        ++done_count;
        continue;
      }
      res.uavs[i].raw.push_back(cur[i]);
      if (flights[i].arrived()) {
        done[i] = 1;
        ++done_count;
        res.uavs[i].reached = true;
      }
    }
  }
  res.frames = frame;
  for (std::size_t i = 0; i < n; ++i)
    if (!res.uavs[i].reached && res.uavs[i].message.empty())
      res.uavs[i].message =
          "goal not reached within " + std::to_string(max_frames) + " frames; raise planner.params.max_frames";

  // Smoothing, UAV by UAV, against the current paths of the peers that can matter: a smoothed
  // point stays within kDrift_steps steps of its raw place, so two UAVs that never come within
  // `reach` of each other at equal frames cannot conflict after smoothing (FrameNeighbours).
  for (std::size_t i = 0; i < n; ++i) res.uavs[i].smoothed = res.uavs[i].raw;
  if (!options.smooth) return res;
  double need_max = base.separation_m;
  for (const UavSpec& u : sc.uavs) need_max = std::max(need_max, 2.0 * u.radius_m);
  const double drift_m = kDrift_steps * step;
  // Endpoints move by at most 2 drifts relative to each other, a frame's relative motion is at
  // most 2 (step + 2 drift) long and its middle lies within half that of an endpoint; a move at
  // frame k is checked over frames k - 1 to k + 1, and raw steps are at most one step long.
  const double reach = need_max + kPlanningMargin_m + step + 4.0 * drift_m + 2.0 * step;
  const FrameNeighbours near(res.uavs, reach);
  for (std::size_t i = 0; i < n; ++i) {
    GroupUav& g = res.uavs[i];
    if (!g.reached) continue;
    auto& pts = g.smoothed;
    auto accept = [&](std::size_t k, const Vec3& c) {
      if ((c - g.raw[k]).norm() > drift_m || !fields[i]->step_safe(pts[k - 1], c, {}) ||
          !fields[i]->step_safe(c, pts[k + 1], {})) {
        ++g.kept_points;
        return false;
      }
      for (const std::uint32_t j : near.at_frame(i, k)) {
        const auto& q = res.uavs[j].smoothed;
        const double need = std::max(base.separation_m, sc.uavs[i].radius_m + sc.uavs[j].radius_m) + 1e-3;
        if (point_segment_distance(Vec3::Zero(), pts[k - 1] - at(q, k - 1), c - at(q, k)) < need ||
            point_segment_distance(Vec3::Zero(), c - at(q, k), pts[k + 1] - at(q, k + 1)) < need) {
          ++g.kept_points;
          return false;
        }
      }
      return true;
    };
    g.smoothed_points = smooth_triples(pts, deg_to_rad(options.smoothing_threshold_deg), accept);
  }
  return res;
}

}  // namespace uavplan
