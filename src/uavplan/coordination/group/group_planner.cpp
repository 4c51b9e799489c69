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

// An escape route's grid holds at most this many cells (FieldGuide).
constexpr std::int64_t kGuideCells = 2'000'000;

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

// P3's group planning: every UAV's field and the group's one step and frame time, the frames
// (each UAV in turn one step, the earlier UAVs with this frame's motion as time-stamped
// obstacles, the later ones where they are), then the smoothing. One method per stage.
class GroupPlanning {
 public:
  GroupPlanning(const Scenario& sc, const ApfOptions& options, const StopCondition& stop)
      : sc_(sc), options_(options), stop_(stop), n_(sc.uavs.size()), cur_(n_), prev_(n_), done_(n_, 0) {
    base_ = options;
    base_.separation_m = sc.mission.separation_m;
    // The escape route of the UAV moving now, around the UAVs that are done.
    guide_ = [this](const Vec3& from, const Vec3& to) {
      keep_out_.clear();
      for (std::size_t j = 0; j < n_; ++j)
        if (j != moving_ && done_[j])
          keep_out_.push_back(
              {cur_[j],
               std::max(base_.separation_m, sc_.uavs[moving_].radius_m + sc_.uavs[j].radius_m) + kPlanningMargin_m});
      return guide_for(moving_).route(from, to, keep_out_);
    };
  }

  GroupResult run() {
    resolve_fields();
    const double longest = start_uavs();
    fly(options_.max_frames > 0 ? options_.max_frames : static_cast<int>(4.0 * longest / step_) + 500);
    for (std::size_t i = 0; i < n_; ++i) res_.uavs[i].smoothed = res_.uavs[i].raw;
    if (options_.smooth) smooth();
    return std::move(res_);
  }

 private:
  void resolve_fields();
  double start_uavs();
  void fly(int max_frames);
  void smooth();
  FieldGuide& guide_for(std::size_t i);
  Vec3 step_uav(std::size_t i, const CellIndex& index, double max_radius, std::uint64_t& done_count);

  const Scenario& sc_;
  const ApfOptions& options_;
  const StopCondition& stop_;
  std::size_t n_;
  ApfOptions base_;
  GroupResult res_;
  double step_ = 0.0;
  std::vector<ApfOptions> resolved_;
  std::vector<std::unique_ptr<PotentialField>> fields_;
  std::vector<FieldFlight> flights_;
  std::vector<Vec3> cur_, prev_;
  std::vector<char> done_;
  // Escape routes (FieldGuide): one grid per distinct body, built at the first stall.
  std::vector<std::pair<std::size_t, std::unique_ptr<FieldGuide>>> guides_;
  std::vector<KeepOut> keep_out_;
  std::vector<PeerMotion> peers_;
  std::size_t moving_ = 0;
  FieldFlight::Guide guide_;
};

// One step and one frame time for the whole group: the smallest derived step, flown by the
// slowest UAV in one frame; each UAV's field resolved for that step.
void GroupPlanning::resolve_fields() {
  double step = 1e300, slowest = 1e300;
  for (const UavSpec& u : sc_.uavs) {
    resolved_.push_back(apf_resolved(base_, u, sc_.world));
    step = std::min(step, resolved_.back().step_m);
    slowest = std::min(slowest, u.speed.cruise_mps);
  }
  step_ = step;
  res_.step_m = step;
  res_.frame_s = step / slowest;
  for (std::size_t i = 0; i < n_; ++i) {
    resolved_[i].step_m = step;
    resolved_[i] = apf_resolved(resolved_[i], sc_.uavs[i], sc_.world);
    fields_.push_back(std::make_unique<PotentialField>(sc_.world, sc_.uavs[i], resolved_[i]));
  }
}

// Every UAV at its start; those without a goal, that cannot fly or are there already are done.
// Returns the longest straight distance still to fly.
double GroupPlanning::start_uavs() {
  double longest = 0.0;
  for (std::size_t i = 0; i < n_; ++i) {
    GroupUav g;
    g.id = sc_.uavs[i].id;
    cur_[i] = sc_.uavs[i].start;
    g.raw.push_back(cur_[i]);
    const Vec3 goal = sc_.uavs[i].goal.value_or(cur_[i]);
    flights_.emplace_back(*fields_[i], cur_[i], goal, -1);  // stalls in a crowd pass: the frame budget bounds them
    if (!sc_.uavs[i].goal) {
      g.message = "no goal given";
      done_[i] = 1;
    } else if (const std::string why = infeasible(sc_, i); !why.empty()) {
      g.message = why;
      done_[i] = 1;
    } else if (goal == cur_[i]) {
      g.reached = true;
      done_[i] = 1;
    } else {
      longest = std::max(longest, (goal - cur_[i]).norm());
    }
    res_.uavs.push_back(std::move(g));
  }
  return longest;
}

FieldGuide& GroupPlanning::guide_for(std::size_t i) {
  const UavSpec& u = sc_.uavs[i];
  for (auto& [j, g] : guides_) {
    const UavSpec& v = sc_.uavs[j];
    if (v.radius_m == u.radius_m && v.max_climb_rad == u.max_climb_rad && v.ceiling_m == u.ceiling_m) return *g;
  }
  guides_.emplace_back(i, std::make_unique<FieldGuide>(sc_.world, u, step_, kGuideCells, stop_));
  return *guides_.back().second;
}

// UAV i's step of this frame among its peers (within its reach + a step: the index holds the
// frame's starting positions and a UAV moves at most a step within the frame); an escape route,
// when it stalls, goes around the UAVs that are done (they never move again).
Vec3 GroupPlanning::step_uav(std::size_t i, const CellIndex& index, double max_radius, std::uint64_t& done_count) {
  const UavSpec& u = sc_.uavs[i];
  const double reach = resolved_[i].r_rep_m + base_.separation_m + 2 * step_ + u.radius_m + max_radius;
  peers_.clear();
  index.near(cur_[i], [&](std::uint32_t j) {
    if (j == i || (cur_[j] - cur_[i]).norm() > reach + step_) return;
    peers_.push_back({j < i ? prev_[j] : cur_[j], cur_[j], sc_.uavs[j].radius_m});
  });
  moving_ = i;
  return flights_[i].advance(peers_, guide_, done_count);
}

void GroupPlanning::fly(int max_frames) {
  double max_radius = 0.0, max_reach = 0.0;
  for (const UavSpec& u : sc_.uavs) max_radius = std::max(max_radius, u.radius_m);
  for (const ApfOptions& o : resolved_)
    max_reach = std::max(max_reach, o.r_rep_m + base_.separation_m + 2 * step_ + 2 * max_radius);
  CellIndex index;
  // The keep-outs' version for the escape routes: they change when a UAV is done.
  std::uint64_t done_count = static_cast<std::uint64_t>(std::count(done_.begin(), done_.end(), 1));
  int frame = 0;
  for (; frame < max_frames && done_count < n_ && !stop_.should_stop(frame); ++frame) {
    prev_ = cur_;
    index.build(prev_, max_reach + 3 * step_);
    for (std::size_t i = 0; i < n_; ++i) {
      if (done_[i]) continue;
      cur_[i] = step_uav(i, index, max_radius, done_count);
      if (flights_[i].failed()) {
        res_.uavs[i].message = flights_[i].message() + " at frame " + std::to_string(frame);
        done_[i] = 1;
        ++done_count;
        continue;
      }
      res_.uavs[i].raw.push_back(cur_[i]);
      if (flights_[i].arrived()) {
        done_[i] = 1;
        ++done_count;
        res_.uavs[i].reached = true;
      }
    }
  }
  res_.frames = frame;
  for (std::size_t i = 0; i < n_; ++i)
    if (!res_.uavs[i].reached && res_.uavs[i].message.empty())
      res_.uavs[i].message =
          "goal not reached within " + std::to_string(max_frames) + " frames; raise planner.params.max_frames";
}

// Smoothing, UAV by UAV, against the current paths of the peers that can matter: a smoothed
// point stays within kDrift_steps steps of its raw place, so two UAVs that never come within
// `reach` of each other at equal frames cannot conflict after smoothing (FrameNeighbours).
void GroupPlanning::smooth() {
  double need_max = base_.separation_m;
  for (const UavSpec& u : sc_.uavs) need_max = std::max(need_max, 2.0 * u.radius_m);
  const double drift_m = kDrift_steps * step_;
  // Endpoints move by at most 2 drifts relative to each other, a frame's relative motion is at
  // most 2 (step + 2 drift) long and its middle lies within half that of an endpoint; a move at
  // frame k is checked over frames k - 1 to k + 1, and raw steps are at most one step long.
  const double reach = need_max + kPlanningMargin_m + step_ + 4.0 * drift_m + 2.0 * step_;
  const FrameNeighbours near(res_.uavs, reach);
  for (std::size_t i = 0; i < n_; ++i) {
    GroupUav& g = res_.uavs[i];
    if (!g.reached) continue;
    auto& pts = g.smoothed;
    auto accept = [&](std::size_t k, const Vec3& c) {
      if ((c - g.raw[k]).norm() > drift_m || !fields_[i]->step_safe(pts[k - 1], c, {}) ||
          !fields_[i]->step_safe(c, pts[k + 1], {})) {
        ++g.kept_points;
        return false;
      }
      for (const std::uint32_t j : near.at_frame(i, k)) {
        const auto& q = res_.uavs[j].smoothed;
        const double need = std::max(base_.separation_m, sc_.uavs[i].radius_m + sc_.uavs[j].radius_m) + 1e-3;
        if (point_segment_distance(Vec3::Zero(), pts[k - 1] - at(q, k - 1), c - at(q, k)) < need ||
            point_segment_distance(Vec3::Zero(), c - at(q, k), pts[k + 1] - at(q, k + 1)) < need) {
          ++g.kept_points;
          return false;
        }
      }
      return true;
    };
    g.smoothed_points = smooth_triples(pts, deg_to_rad(options_.smoothing_threshold_deg), accept);
  }
}

}  // namespace

GroupResult plan_group(const Scenario& sc, const ApfOptions& options, const StopCondition& stop) {
  return GroupPlanning(sc, options, stop).run();
}

}  // namespace uavplan
