// Potential-field planning (P3, Wei et al. 2018) and the traditional field it improves on.
//
// One step: F = l (F_att + F_rep) / |F_att + F_rep|, a fixed step l (P3 eq. 3).
// Attraction (P3 eq. 4, with its swapped inequality signs read the right way round):
//   F_att = K_a min(R, R_a0) P_a, R the distance to the goal, P_a the unit vector to it.
// Repulsion per obstacle with clearance r < R_r0 (P3 eq. 5):
//   F_rep = K_r sqrt(R) [(1/r^2)(1/r - 1/R_r0) + (1/r - 1/R_r0)^2] P_r,
// P_r the unit vector from the obstacle's nearest point to the UAV; sqrt(R) fades the repulsion
// near the goal. Sector rule: of the obstacles inside one 15-degree sector (in 3-D: a cell of
// 15 x 15 degrees of azimuth and elevation) around the UAV only the nearest counts.
// The traditional field: F_att = K_a R P_a, F_rep = K_r (1/r - 1/R_r0) / r^2 P_r, every obstacle.
//
// Our additions, so that every emitted step is safe: a step whose segment would come closer to
// an obstacle than the UAV radius, or to a peer than the separation, is replaced by the nearest
// safe direction (rotated in 15-degree steps), else the UAV holds; steps keep the climb limit;
// progress is watched, and a UAV that has not come a step closer in 20 frames is in a local
// minimum: it escapes sideways (perpendicular to the goal direction, left and right in turn)
// like a bug algorithm until it is a step closer to the goal than where it was caught, at most 8
// times, before it is declared stalled. Routes get the same turn shaping as every planner (turn_limits.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"
#include "uavplan/vehicle/uav.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct ApfOptions {
  bool improved = true;       // P3's field; false: the traditional one
  double step_m = 0.0;        // l; 0 = derived (apf_defaults)
  double k_att = 1.0;         // K_a
  double r_att_m = 0.0;       // R_a0; 0 = 10 l
  double k_rep = 0.0;         // K_r; 0 = balances attraction at r = R_r0 / 2
  double r_rep_m = 0.0;       // R_r0; 0 = max(5 l, 2 separation, 3 radius)
  double sector_deg = 15.0;
  int max_frames = 0;         // 0 = 4 x straight distance / l + 500
  double separation_m = 0.0;  // peers are obstacles closer than this (the mission's)
  bool smooth = true;         // P3's triple smoothing afterwards (the traditional field: never)
  double smoothing_threshold_deg = 5.0;

  static ApfOptions from_params(const Params& params, bool improved);
};

// Options with every derived value filled for this UAV and world. The derived step is half the
// larger of the separation and the UAV's diameter, kept within [extent / 2000, extent / 50].
ApfOptions apf_resolved(const ApfOptions& options, const UavSpec& uav, const World& world);

// Another UAV as an obstacle during one frame: moving from `from` to `to`.
struct PeerMotion {
  Vec3 from, to;
  double radius_m = 0.0;
};

class PotentialField {
 public:
  PotentialField(const World& world, const UavSpec& uav, const ApfOptions& resolved);

  // The field's unit direction at p (no step safety).
  Vec3 direction(const Vec3& p, const Vec3& goal, std::span<const PeerMotion> peers) const;
  // One safe step from p (see the header comment); `escape` (+1 left, -1 right, 0 none) steps
  // perpendicular to the goal direction instead. Returns p itself when it must hold.
  Vec3 step(const Vec3& p, const Vec3& goal, std::span<const PeerMotion> peers, int escape) const;
  bool step_safe(const Vec3& a, const Vec3& b, std::span<const PeerMotion> peers) const;

  const ApfOptions& options() const { return o_; }

 private:
  const World* world_;
  UavSpec uav_;
  ApfOptions o_;
  double inflation_m_;
};

// Flies one UAV alone from start to goal; the waypoints are the frames. Failure: stalled or
// out of frames, with the reason.
struct ApfRun {
  bool reached = false;
  std::vector<Vec3> points;
  std::string message;
};

// Tracks progress and escapes; shared by the single-UAV planner and the group.
class StallWatch {
 public:
  // Returns whether the next step should escape; sets `stalled` when out of escapes.
  // `escape_frames` caps one escape.
  bool update(double distance_to_goal, double step_m, int escape_frames);
  bool stalled() const { return stalled_; }
  // +1: escape to the left of the goal direction, -1: to the right (alternating per escape).
  int side() const { return escapes_ % 2 == 1 ? 1 : -1; }

 private:
  std::vector<double> history_;
  double caught_at_ = 0.0;
  int escape_left_ = 0;
  int escapes_ = 0;
  bool stalled_ = false;
};

ApfRun run_apf(const PotentialField& field, const Vec3& start, const Vec3& goal, const StopCondition& stop = {});

class ApfPlanner final : public Planner {
 public:
  ApfPlanner(ApfOptions options) : options_(options) {}
  std::string_view name() const override { return options_.improved ? "apf" : "apf_traditional"; }
  const ApfOptions& options() const { return options_; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  ApfOptions options_;
};

// P3's smoothing (sec. 3): over triples A, B, C, when the turn at B exceeds the threshold, B
// becomes the midpoint of B and midpoint(A, C); sweeps repeat until nothing changes (at most
// `max_sweeps`). `accept(i, candidate)` may refuse a move (a conflict): then B stays.
template <class Accept>
int smooth_triples(std::vector<Vec3>& pts, double threshold_rad, Accept&& accept, int max_sweeps = 200) {
  int changed_total = 0;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    int changed = 0;
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
      const Vec3 ab = pts[i] - pts[i - 1], bc = pts[i + 1] - pts[i];
      if (ab.norm() <= 1e-12 || bc.norm() <= 1e-12) continue;
      const double turn = std::acos(std::clamp(ab.dot(bc) / (ab.norm() * bc.norm()), -1.0, 1.0));
      if (turn <= threshold_rad) continue;
      const Vec3 candidate = 0.5 * (pts[i] + 0.5 * (pts[i - 1] + pts[i + 1]));
      if ((candidate - pts[i]).norm() <= 1e-9 || !accept(i, candidate)) continue;
      pts[i] = candidate;
      ++changed;
    }
    changed_total += changed;
    if (changed == 0) break;
  }
  return changed_total;
}

}  // namespace uavplan
