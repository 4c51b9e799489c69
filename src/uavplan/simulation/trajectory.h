// Time-stamped trajectories: between consecutive samples a UAV moves in a straight line at
// constant speed. Before its first sample a UAV is at its first position (waiting to depart);
// after its last it stays at its last (hovering or landed at the goal).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "uavplan/core/vec.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct TrajectorySample {
  double t_s = 0.0;
  Vec3 p = Vec3::Zero();
};
using Trajectory = std::vector<TrajectorySample>;

// Flies the waypoints at `speed_mps`, starting at t = 0 and departing at `depart_s` (holding at
// the start before), with a sample at every waypoint and at most `max_dt_s` between samples.
Trajectory time_route(std::span<const Vec3> waypoints, double speed_mps, double depart_s, double max_dt_s);

// Appends a straight run from the trajectory's last row to `to`, the speed changing evenly from
// v0_mps to v1_mps (taxiing, a take-off roll, a glide, a roll-out): a row every sample_s and at `to`.
void append_straight_run(Trajectory& tr, const Vec3& to, double v0_mps, double v1_mps, double sample_s);

Vec3 position_at(const Trajectory& tr, double t_s);

// How far along its rows a trajectory has been followed: segment `segment`, `fraction` along it.
struct TrackProgress {
  std::size_t segment = 0;
  double fraction = 0.0;
};
// Whether the trajectory, from `at` on, passes within tol_m of p; `at` moves to the first such
// place (a via point visited in order).
bool passes_within(const Trajectory& tr, const Vec3& p, double tol_m, TrackProgress& at);

// The distance flown: the length of the polyline through the rows, summed from the first.
inline double flown_length_m(const Trajectory& tr) {
  double len = 0.0;
  for (std::size_t i = 1; i < tr.size(); ++i) len += (tr[i].p - tr[i - 1].p).norm();
  return len;
}

struct Encounter {
  double distance_m = World::kInf;  // smallest distance (centre to centre for two UAVs)
  double t_s = 0.0;                 // when
  Vec3 where = Vec3::Zero();        // first trajectory's position then
};

// Exact smallest distance between two trajectories at equal times (piecewise linear on the
// merged sample times, so each piece is a closed-form minimum), up to time t_max_s.
Encounter closest_approach(const Trajectory& a, const Trajectory& b,
                           double t_max_s = std::numeric_limits<double>::infinity());
// The same over the times [t_from_s, t_to_s] only.
Encounter closest_approach_between(const Trajectory& a, const Trajectory& b, double t_from_s, double t_to_s);

// Lower bounds on closest_approach for many pairs at once: the common time span cut into
// slices, each trajectory's bounding box per slice; two trajectories are never nearer than
// their nearest pair of boxes of one slice. Pair checks over a group skip the pairs whose bound
// already clears the distance in question.
class SweptBoxes {
 public:
  explicit SweptBoxes(std::span<const Trajectory* const> trajectories, int slices = 64);
  double lower_bound_m(std::size_t i, std::size_t j) const;

  struct NearPair {
    std::uint32_t i, j;  // i < j
    double bound_m;      // lower_bound_m(i, j)
  };
  // Every pair whose lower bound is below `reach_m`, ordered by (i, j); the others are never
  // nearer than `reach_m`. Per slice a sort and sweep along x, so a group's pairs cost about
  // slices * n log n plus the pairs near each other, not n^2.
  std::vector<NearPair> pairs_within(double reach_m) const;
  // The diagonal of all boxes together: pairs_within of more holds every pair.
  double extent_m() const;
  // The time spans (runs of slices) in which trajectories i and j may come nearer than
  // `below_m`: outside them they never do.
  std::vector<std::pair<double, double>> near_spans(std::size_t i, std::size_t j, double below_m) const;
  // closest_approach of trajectories i and j (those this was made of) if it is below `below_m`,
  // measured over the near spans only; else a distance of at least `below_m`.
  Encounter closest_below(std::span<const Trajectory* const> trajectories, std::size_t i, std::size_t j,
                          double below_m) const;

 private:
  int slices_ = 0;
  double t0_s_ = 0.0, width_s_ = 1.0, t1_s_ = 0.0;  // the slices' common span and width
  std::vector<Aabb> boxes_;                         // trajectory-major, `slices_` each
};

// Exact smallest gap between the trajectory and the surface of any moving obstacle;
// `index_out` names the obstacle.
Encounter closest_moving_approach(const World& world, const Trajectory& tr, int* index_out = nullptr);

// The corners of a flown trajectory (rows on a straight line at constant speed dropped).
std::vector<Vec3> trajectory_corners(const Trajectory& tr);

}  // namespace uavplan
