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
// safe direction (rotated in 15-degree steps), else the UAV holds; steps keep the climb limit.
// Progress is watched (FieldFlight): a UAV that has not come a step closer in 20 frames is in a
// local minimum and escapes along a grid A* route (field_guide.h) that the field then follows
// (FieldFlight says when a route is rebuilt and when the UAV has failed).
// Routes get the same turn shaping as every planner (turn_limits.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "uavplan/core/tolerances.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"
#include "uavplan/vehicle/uav.h"
#include "uavplan/world/world.h"

namespace uavplan {

// P3's improved field, or the traditional one it beats.
enum class ApfField { improved, traditional };

struct ApfOptions {
  bool improved = true;  // P3's field; false: the traditional one
  double step_m = 0.0;   // l; 0 = derived (apf_defaults)
  double k_att = 1.0;    // K_a
  double r_att_m = 0.0;  // R_a0; 0 = 10 l
  double k_rep = 0.0;    // K_r; 0 = balances attraction at r = R_r0 / 2
  double r_rep_m = 0.0;  // R_r0; 0 = max(5 l, 2 separation, 3 radius)
  double sector_deg = 15.0;
  int max_frames = 0;         // 0 = 4 x straight distance / l + 500
  double separation_m = 0.0;  // peers are obstacles closer than this (the mission's)
  bool smooth = true;         // P3's triple smoothing afterwards (the traditional field: never)
  double smoothing_threshold_deg = 5.0;

  static ApfOptions from_params(const Params& params, ApfField field);

  // The declaration of its parameters: reads them from r (params.h).

  static ApfOptions read(ParamReader& r, ApfField field);
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

  // The field's unit direction at p (no step safety). With `aim` the attraction points at it
  // instead of the goal (its size and the repulsion's sqrt(R) still use the goal's distance).
  Vec3 direction(const Vec3& p, const Vec3& goal, std::span<const PeerMotion> peers, const Vec3* aim = nullptr) const;
  // One safe step from p (see the header comment). Returns p itself when it must hold.
  Vec3 step(const Vec3& p, const Vec3& goal, std::span<const PeerMotion> peers, const Vec3* aim = nullptr) const;
  bool step_safe(const Vec3& a, const Vec3& b, std::span<const PeerMotion> peers) const;

  const ApfOptions& options() const { return o_; }
  const World& world() const { return *world_; }
  const UavSpec& uav() const { return uav_; }

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
  Reason reason = Reason::no_route;  // when not reached
};

// One UAV flying the field frame by frame, shared by the single-UAV planner and the group.
// Progress is the distance to the goal, or while guided the distance left along the guide
// route; a stall is less than one step of progress in 20 frames. The first stall asks `guide`
// for a route from where the UAV is, and the UAV follows it from then on, the attraction aimed
// at the first route point more than two steps ahead; a later stall asks again only when the
// keep-outs have changed (`keep_out_version`), else it counts against `patience` (stalls on one
// route; negative: no limit, the caller's frame budget bounds the flight). No route fails the
// UAV at once.
class FieldFlight {
 public:
  using Guide = std::function<std::vector<Vec3>(const Vec3& from, const Vec3& goal)>;

  FieldFlight(const PotentialField& field, const Vec3& start, const Vec3& goal, int patience)
      : field_(&field), p_(start), goal_(goal), patience_(patience) {}

  // One frame: moves (or holds) and returns the new position; nothing once arrived or failed.
  const Vec3& advance(std::span<const PeerMotion> peers, const Guide& guide, std::uint64_t keep_out_version = 0);

  const Vec3& position() const { return p_; }
  bool arrived() const { return arrived_; }
  bool failed() const { return failed_; }
  bool guided() const { return !route_.empty(); }
  int stalls() const { return stalls_; }
  const std::string& message() const { return message_; }

  static constexpr int kWindowFrames = 20;

 private:
  double progress_m() const;
  void follow(std::vector<Vec3> route);

  const PotentialField* field_;
  Vec3 p_, goal_;
  int patience_;
  std::vector<Vec3> route_;
  std::vector<double> left_m_;  // route length from each route point to the goal
  std::size_t next_ = 0;        // the route point aimed at
  std::uint64_t route_version_ = 0;
  std::vector<double> history_;
  int stalls_ = 0;
  int stalls_on_route_ = 0;
  bool arrived_ = false;
  bool failed_ = false;
  std::string message_;
};

// `guide` answers the stalls (FieldFlight); empty: a FieldGuide over the field's world, built
// at the first stall.
ApfRun run_apf(const PotentialField& field, const Vec3& start, const Vec3& goal, const FieldFlight::Guide& guide = {},
               const StopCondition& stop = {});

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
  const double cos_threshold = std::cos(std::clamp(threshold_rad, 0.0, kPi));
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    int changed = 0;
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
      const Vec3 ab = pts[i] - pts[i - 1], bc = pts[i + 1] - pts[i];
      const double nab = ab.norm(), nbc = bc.norm();
      if (nab <= 1e-12 || nbc <= 1e-12) continue;
      if (ab.dot(bc) >= cos_threshold * nab * nbc) continue;  // turn within the threshold
      const Vec3 candidate = 0.5 * (pts[i] + 0.5 * (pts[i - 1] + pts[i + 1]));
      if ((candidate - pts[i]).norm() <= kSamePoint_m || !accept(i, candidate)) continue;
      pts[i] = candidate;
      ++changed;
    }
    changed_total += changed;
    if (changed == 0) break;
  }
  return changed_total;
}

}  // namespace uavplan
