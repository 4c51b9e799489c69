// What the planners see of a scenario, so that every planner and mission honours a UAV's
// clearance, its min_agl and a start or goal on the ground without knowing of them:
//  - a UAV's body is its radius plus its clearance (obstacles, terrain and moving obstacles are
//    kept that far; the separation between UAVs counts it too, which only adds margin);
//  - the ground is raised by the largest min_agl of the scenario's UAVs (the terrain, and a
//    floor over the bottom of the bounds), and the sky above the smallest max_agl closed;
//  - a UAV standing on the ground at its start is planned from its lift-off point straight above
//    (its body and min_agl clear of the ground), one whose goal is on the ground to its
//    touch-down point straight above;
//  - UAVs sharing a goal end at distinct arrival points (arrival_points.h);
//  - a mission that times the take-off and landing legs itself (Mission::times_ground_legs,
//    from PlanningView::ground) flies them within its own timing; for the others the planning's
//    t = 0 is when the last UAV on the ground has climbed to its lift-off point, and moving
//    obstacles are shifted by that time, so the plan keeps every encounter.
// to_scenario() turns the plan back: the legs a mission did not fly added, times shifted.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/coordination/ground_heights.h"
#include "uavplan/coordination/mission.h"

namespace uavplan {

struct PlanningView {
  bool identity = true;                         // nothing to change: plan the scenario as it is
  Scenario scenario;                            // what is planned (when not the identity)
  double takeoff_s = 0.0;                       // the planning's t = 0 in the plan's time
  std::vector<std::optional<Vec3>> lift_off;    // per UAV, for a start on the ground
  std::vector<std::optional<Vec3>> touch_down;  // per UAV, for a goal on the ground
  GroundPoints ground;                          // where those legs begin and end on the ground
  std::vector<std::string> arrival_problem;     // per UAV: a shared goal without room (it fails)
};

// Who times the take-off and landing legs: the plan shifted by the longest take-off (the legs
// added around the mission's plan), or the mission itself (Mission::times_ground_legs).
enum class GroundLegTiming { shifted, by_mission };
// The sky above a max_agl band over terrain: closed by obstacles (what planners see), or left
// open where only points are checked against the band directly (placement_problems).
enum class BandTop { closed, open };
PlanningView planning_view(const Scenario& scenario, GroundLegTiming timing = GroundLegTiming::shifted,
                           BandTop band_top = BandTop::closed);

// Per UAV: why its start or goal cannot be planned from or to once the view applies (on the
// ground: its column; in the air: within min_agl of the ground, or its body and clearance not
// clear of obstacles and terrain), or empty. Checked at load, so planning never meets one.
struct PlacementProblem {
  std::string start, goal;
};
std::vector<PlacementProblem> placement_problems(const Scenario& scenario);

// The plan of view.scenario as a plan of the scenario: UAV plans get the take-off and landing
// legs they do not fly yet (at cruise speed, rows at most max_dt_s apart): a take-off replaces
// a wait at the lift-off point long enough for the climb, else it comes first and the flight
// after it is shifted.
void to_scenario(const PlanningView& view, const Scenario& scenario, Plan& plan, double max_dt_s);

}  // namespace uavplan
