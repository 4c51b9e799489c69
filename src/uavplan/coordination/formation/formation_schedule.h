// A formation's nominal flight (P1 sec. 2.4): every UAV holds its slot of the shape in a frame
// turning with the reference route's heading. All UAVs share one clock: knots tau_k with a
// position per UAV at each. Between knots a UAV flies straight at a constant speed:
//  - form-up: from its start to its slot at the route's first point, all arriving together;
//  - cruise: the reference pursues the route (pure pursuit, a turn radius of twice the shape's
//    reach, 5 deg of turn a step at most), the shape turning with its heading, so that a graph
//    route's many short edges are one smooth curve and no slot backs up at a corner;
//  - where any slot's chord of that path is not clear (opt.slot_clear), along the route itself:
//    its near-collinear wiggles (points within 1 % of the shape's reach of the straight line past
//    them) flown straight past, each segment as the slot's translate, each corner an arc inside
//    it where one fits and is clear, else the shape turning about the corner (chords);
//  - approach: `approach_m` before the route's end the shape turns as the goals lie (as it goes
//    in where the way is straight and long enough for no slot to back up, else where the
//    approach begins) and flies into the goals (each UAV's slot at the end), all arriving
//    together: every UAV moves until the end, none waits at its goal for the others.
#pragma once

#include <functional>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

struct FormationSchedule {
  std::vector<double> knots_s;           // tau_k, from 0
  std::vector<std::vector<Vec3>> slots;  // per UAV, its position at each knot
  std::size_t form_up_knot = 1;          // the knot where the formation is formed (route start)
  std::size_t final_knot = 0;            // the knot where the approach to the goals begins

  double end_s() const { return knots_s.back(); }
  // UAV i's nominal position at clock tau.
  Vec3 at(std::size_t i, double tau_s) const;
  // UAV i's nominal path from tau0 to tau1 (both ends included, corners between).
  std::vector<Vec3> path(std::size_t i, double tau0_s, double tau1_s) const;
  // Length of that path.
  double length(std::size_t i, double tau0_s, double tau1_s) const;
  // The knot interval [k, k+1] holding tau.
  std::size_t interval(double tau_s) const;
};

// The shape's slots are taken relative to their centroid (the reference point). `route` is the
// reference's route (at least one point), `speed_mps` the formation's speed, `approach_m` the
// approach's length along the route (0: the end leg from the route's end into the goals only).
struct FormationScheduleOptions {
  double speed_mps = 1.0;
  double approach_m = 0.0;
  // Whether UAV i may fly straight from a to b (static obstacles, bounds); a corner's arc cuts
  // inside the route, so it is flown only where every slot's chords are clear (none: all are).
  std::function<bool(std::size_t i, const Vec3& a, const Vec3& b)> slot_clear;
  // The least distance UAVs i and j keep (none: 0). The form-up flies each UAV straight into its
  // slot at the route's first heading where that keeps every pair apart.
  std::function<double(std::size_t i, std::size_t j)> pair_need_m;
};
FormationSchedule formation_schedule(const std::vector<Vec3>& route, const std::vector<Vec3>& shape,
                                     const std::vector<Vec3>& starts, const std::vector<Vec3>& goals,
                                     const FormationScheduleOptions& options);

// The smallest distance between UAVs i and j on the schedule within knot interval k (their
// relative motion is linear there).
double schedule_gap_m(const FormationSchedule& s, std::size_t i, std::size_t j, std::size_t k);

}  // namespace uavplan
