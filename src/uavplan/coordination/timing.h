// Timing routes against what is already flying: the earliest departure at which a route flown
// at cruise speed keeps clear of the moving obstacles and of the UAVs committed before it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/stop.h"

namespace uavplan {

// Gaps are kept this much above the limit so that rounding in the written plan cannot break them.
inline constexpr double kTimingMargin_m = 1e-3;

// UAVs already timed, with their plans.
using Committed = std::vector<std::pair<const UavSpec*, const UavPlan*>>;

// Whether a timed UAV keeps clear of the moving obstacles (known in advance to it), or leaves
// them to its sensors (it meets them in the loop).
enum class MovingObstacles { avoided, sensed };

struct Conflict {
  bool any = false;
  std::string what;
};

// The first conflict of a trajectory with the moving obstacles (unless left out) or a committed UAV.
Conflict find_conflict(const Scenario& sc, const UavSpec& uav, const Trajectory& tr, const Committed& committed,
                       MovingObstacles moving = MovingObstacles::avoided);

// The earliest departure delay, in delay_step_s steps up to max_delay_s, at which the route flown
// at cruise speed keeps clear of the moving obstacles and of the UAVs committed before it; when
// none does, the first conflict met (for the message). A stop ends the search (`stopped`).
struct Departure {
  bool placed = false;
  bool stopped = false;
  double delay_s = 0.0;
  Trajectory trajectory;
  Conflict first;
};
Departure earliest_departure(const Scenario& sc, const UavSpec& u, const std::vector<Vec3>& waypoints,
                             double max_delay_s, const Committed& committed, double delay_step_s,
                             double max_sample_dt_s, const StopCondition& stop,
                             MovingObstacles moving = MovingObstacles::avoided);

// A UAV's entry in the plan: solved with its route and trajectory, or failed with the message.
UavPlan flown_plan(const std::string& id, bool ok, std::string message, std::vector<Vec3> waypoints,
                   Trajectory trajectory);

// Every scenario UAV failed with the same message (a mission that cannot plan at all).
void fail_all(const Scenario& scenario, const std::string& why, Plan& plan);

}  // namespace uavplan
