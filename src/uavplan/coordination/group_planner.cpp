#include "uavplan/coordination/group_planner.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "uavplan/core/geometry.h"
#include "uavplan/core/units.h"

namespace uavplan {

Trajectory frames_to_trajectory(const std::vector<Vec3>& frames, double frame_s) {
  Trajectory tr;
  for (std::size_t k = 0; k < frames.size(); ++k) tr.push_back({static_cast<double>(k) * frame_s, frames[k]});
  return tr;
}

namespace {

// Position at frame k (held at the last one afterwards).
const Vec3& at(const std::vector<Vec3>& f, std::size_t k) { return f[std::min(k, f.size() - 1)]; }

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
  std::vector<StallWatch> watch(n);
  double longest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    GroupUav g;
    g.id = sc.uavs[i].id;
    cur[i] = sc.uavs[i].start;
    g.raw.push_back(cur[i]);
    if (!sc.uavs[i].goal) {
      g.message = "no goal given";
      done[i] = 1;
    } else {
      longest = std::max(longest, (*sc.uavs[i].goal - cur[i]).norm());
    }
    res.uavs.push_back(std::move(g));
  }
  const int max_frames = options.max_frames > 0 ? options.max_frames : static_cast<int>(4.0 * longest / step) + 500;
  const int escape_frames = static_cast<int>(2.0 * longest / step) + 50;
  std::vector<PeerMotion> peers;
  int frame = 0;
  for (; frame < max_frames && std::count(done.begin(), done.end(), 0) > 0 && !stop.should_stop(frame); ++frame) {
    prev = cur;
    for (std::size_t i = 0; i < n; ++i) {
      if (done[i]) continue;
      const UavSpec& u = sc.uavs[i];
      const Vec3& goal = *u.goal;
      // Peers near enough to matter: earlier UAVs with this frame's motion, later ones where they are.
      const double reach = resolved[i].r_rep_m + base.separation_m + 2 * step + 2 * u.radius_m;
      peers.clear();
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i || (cur[j] - cur[i]).norm() > reach + step) continue;
        peers.push_back({j < i ? prev[j] : cur[j], cur[j], sc.uavs[j].radius_m});
      }
      const bool escape = watch[i].update((cur[i] - goal).norm(), step, escape_frames);
      if (watch[i].stalled()) {
        res.uavs[i].message = "stalled in a local minimum at frame " + std::to_string(frame);
        done[i] = 1;
        continue;
      }
      cur[i] = fields[i]->step(cur[i], goal, peers, escape ? watch[i].side() : 0);
      res.uavs[i].raw.push_back(cur[i]);
      if (cur[i] == goal) {
        done[i] = 1;
        res.uavs[i].reached = true;
      }
    }
  }
  res.frames = frame;
  for (std::size_t i = 0; i < n; ++i)
    if (!res.uavs[i].reached && res.uavs[i].message.empty())
      res.uavs[i].message = "goal not reached within " + std::to_string(max_frames) + " frames";

  // Smoothing, UAV by UAV, against everyone's current paths.
  for (std::size_t i = 0; i < n; ++i) res.uavs[i].smoothed = res.uavs[i].raw;
  if (!options.smooth) return res;
  for (std::size_t i = 0; i < n; ++i) {
    GroupUav& g = res.uavs[i];
    if (!g.reached) continue;
    auto& pts = g.smoothed;
    auto accept = [&](std::size_t k, const Vec3& c) {
      if (!fields[i]->step_safe(pts[k - 1], c, {}) || !fields[i]->step_safe(c, pts[k + 1], {})) {
        ++g.kept_points;
        return false;
      }
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
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
