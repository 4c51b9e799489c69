// The closed-loop simulator: a fixed control and sensing period T; every period each UAV's
// sensor refreshes its tracks (sensing.h), a FlightController sets the routes and speeds from
// what the UAVs know, and the vehicles fly them for T (point masses following their routes at
// the commanded speed within their limits, exactly, so every vertex and period end is a sample).
// What the UAVs flew is their trajectory. Moving obstacles and UAVs flying fixed trajectories
// move by the truth; the controller sees them only through the sensors.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/simulation/sensing.h"
#include "uavplan/simulation/trajectory.h"
#include "uavplan/vehicle/uav.h"
#include "uavplan/world/world.h"

namespace uavplan {

struct LoopUav {
  const UavSpec* spec = nullptr;
  std::vector<Vec3> route;  // the route it sets out on; the first point is where it starts
  double sensor_range_m = std::numeric_limits<double>::infinity();
  double depart_s = 0.0;  // it waits at its start until the first period from then
};

// A UAV that flies a fixed trajectory (planned before, not in the loop): an object to sense.
struct ScriptedUav {
  const UavSpec* spec = nullptr;
  const Trajectory* trajectory = nullptr;
};

struct FlightState {
  const UavSpec* spec = nullptr;
  Vec3 position = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();  // of the last motion (the start heading before it moves)
  bool moved = false;              // has it moved yet (whether `direction` is a flown one)
  std::vector<Vec3> route;         // ahead of it: route[0] is the next point it flies to
  double speed_mps = 0.0;          // commanded; flown within [min, max] (0 hovers when min is 0)
  double depart_s = 0.0;           // it does not move before (a controller may move it earlier)
  bool done = false;               // flew its whole route (it stays there, keeping watch)
  Trajectory flown;
};

class FlightController {
 public:
  virtual ~FlightController() = default;
  // Called every period with each UAV's state and sensor; may change routes and speeds (a UAV
  // that is done and is given a route flies again).
  virtual void control(double t_s, std::span<FlightState> uavs, std::span<const Sensor> sensors) = 0;
  // Whether the flight goes on though every UAV has flown its route (a group waiting where it is
  // for one of its own to catch up has not arrived).
  virtual bool waiting() const { return false; }
};

// The loop ends when every UAV is done and nothing that moves (by the truth) will come within
// touching distance of one of them again (a moving obstacle: the radii; a UAV flying a fixed
// trajectory: the separation, at least the radii), or at the horizon.
struct LoopOptions {
  double step_s = 1.0;           // T
  double horizon_s = 3600.0;     // UAVs not done by then stop where they are
  double max_sample_dt_s = 1.0;  // longest time between trajectory rows
  double separation_m = 0.0;
};

struct LoopResult {
  std::vector<FlightState> uavs;  // in the order given; `flown` is what each flew
  int steps = 0;
  bool stopped = false;  // by the stop condition or the horizon
};

LoopResult fly_closed_loop(const World& world, std::span<const LoopUav> uavs, std::span<const ScriptedUav> scripted,
                           FlightController& controller, const LoopOptions& options, const StopCondition& stop);

// Flies a point mass along `route` from `state` for dt at its commanded speed (clamped to its
// limits), recording a row at every vertex reached and at the end; done when the route is flown.
// A UAV whose last row is before t_s waited there: a row at t_s comes first.
void advance(FlightState& state, double t_s, double dt_s);

// Inserts rows so that no two are more than max_dt_s apart (motion between rows is straight).
Trajectory densified(const Trajectory& tr, double max_dt_s);

}  // namespace uavplan
