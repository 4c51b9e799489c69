// A formation's nominal flight (P1 sec. 2.4): every UAV holds its slot of the shape in a frame
// turning with the reference route's heading. All UAVs share one clock: knots tau_k with a
// position per UAV at each. Between knots a UAV flies straight at a constant speed:
//  - form-up: from its start to its slot at the route's first point, all arriving together;
//  - each route segment: the slot's translate of the segment, at the formation's speed;
//  - each corner: the slot turns about the corner (a chord), the widest turn at that speed;
//  - end: from the slot at the last point to the UAV's goal (its slot at the end), together.
#pragma once

#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

struct FormationSchedule {
  std::vector<double> knots_s;           // tau_k, from 0
  std::vector<std::vector<Vec3>> slots;  // per UAV, its position at each knot
  std::size_t form_up_knot = 1;          // the knot where the formation is formed (route start)
  std::size_t final_knot = 0;            // the knot where the end leg to the goals begins

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
// reference's route (at least one point), `speed_mps` the formation's speed.
FormationSchedule formation_schedule(const std::vector<Vec3>& route, const std::vector<Vec3>& shape,
                                     const std::vector<Vec3>& starts, const std::vector<Vec3>& goals, double speed_mps);

// The smallest distance between UAVs i and j on the schedule within knot interval k (their
// relative motion is linear there).
double schedule_gap_m(const FormationSchedule& s, std::size_t i, std::size_t j, std::size_t k);

}  // namespace uavplan
