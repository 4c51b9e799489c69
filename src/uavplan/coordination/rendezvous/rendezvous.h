// Simultaneous arrival of several UAVs at one goal by route-length control (P4 sec. 3-4):
// pre-plan every UAV with directional A*, take the longest route as the target P_max, and bring
// each shorter one into [P_max - epsilon, P_max] (so all lengths lie within epsilon of each
// other) by, in turn: (1) the variable-step multi-point search (L from 1 to L_max step 0.2,
// M from 3 to 6, keep the closest), (2) a loiter circle at the start (P4 eq. 9-11), (3) a virtual
// spherical threat (P4 eq. 12-13), adjust-R then move-H. Where none fits, two extensions: a
// loiter of several laps, on either side, at the start or a later waypoint; a detour waypoint
// beside a segment for a length too short to loiter. With equal speeds equal lengths are equal
// arrival times.
#pragma once

#include <string>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/status.h"
#include "uavplan/core/stop.h"
#include "uavplan/planning/search/directional_astar.h"

namespace uavplan {

enum class RendezvousStep { none, preplanned, multi_point, loiter, virtual_adjust_r, virtual_move_h, detour };
std::string_view to_string(RendezvousStep s);

// One UAV's outcome (solved, or failed with the reason) and its route.
struct RendezvousUav : Outcome {
  std::string id;
  std::vector<Vec3> waypoints;
  double preplanned_m = 0.0, final_m = 0.0;
  RendezvousStep step = RendezvousStep::none;
  std::string detail;  // L and M, loiter radius, virtual threat radius and centre, or why it failed
};

struct RendezvousResult {
  double target_m = 0.0;  // P_max
  double epsilon_m = 0.0;
  std::vector<RendezvousUav> uavs;
  int searches = 0;            // directional searches run
  std::uint64_t expanded = 0;  // nodes they expanded
};

// epsilon: the mission's arrival_tolerance, or one lattice cell when it has none.
RendezvousResult plan_rendezvous(const Scenario& scenario, const DirectionalAStarPlanner& planner,
                                 const StopCondition& stop);

}  // namespace uavplan
