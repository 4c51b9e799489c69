// Space-time deconfliction of a routes mission (`deconfliction: space_time`): the UAVs without
// sensors planned together in space and time on a lattice over the planning view's world
// (uav_lattice.h), waits allowed, so that crossing traffic passes instead of waiting for a
// departure slot. Each move takes one tick, the longest edge at the slowest UAV's cruise speed
// (no UAV flies above its cruise speed); moves steeper than the smallest climb limit are left
// out. The method: prioritised planning (eight orders; safe intervals, safe_interval_astar.h), then
// ECBS (w = 1.3) with a bounded number of high-level nodes where it finds none; or one of them, or
// CBS, by `space_time_method`.
//
// What it plans is checked as the verifier checks it before it is claimed: separation on the
// trajectories (take-off and landing legs too), moving obstacles, turn and climb limits and the
// via points; a UAV that fails a check is `failed` with the reason, never flown.
#pragma once

#include <cstddef>
#include <vector>

#include "uavplan/coordination/mission.h"
#include "uavplan/coordination/spacetime/mapf.h"

namespace uavplan {

struct SpaceTimeRoutesOptions {
  MapfMethod method = MapfMethod::automatic;  // automatic: prioritised, then ECBS
  double cell_m = 0.0;                        // lattice spacing; 0: lattice_cell_m
};

// Plans the UAVs `which` (indices into sc.uavs, each with a goal) into plan.uavs[i] (which must
// have one entry per scenario UAV): solved with its route and trajectory, or failed with why.
void plan_space_time(const Scenario& sc, const MissionContext& ctx, const std::vector<std::size_t>& which,
                     const SpaceTimeRoutesOptions& o, Plan& plan);

// Each UAV of `which` alone on the lattice plan_space_time builds for them (the others away): the
// yardstick of what deconfliction costs. `found` false where it has no route or no lattice.
struct LoneFlight {
  bool found = false;
  double arrival_s = 0.0, length_m = 0.0;
};
std::vector<LoneFlight> lone_space_time_flights(const Scenario& sc, const MissionContext& ctx,
                                                const std::vector<std::size_t>& which, const SpaceTimeRoutesOptions& o);

}  // namespace uavplan
