// P5's fine planning (sec. 3): a group of UAVs, each flown through its autopilot model (P5 eq. 1),
// sample by sample; those in formation under the consensus laws (consensus.h), the shape given
// in the frame turned by the desired heading phi* (forward, left, up: P5 fig. 6), the others on
// their own commands. Each UAV's flight is recorded as trajectory rows.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "uavplan/coordination/formation_mission/consensus.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

struct FormationGroupOptions {
  ConsensusGains gains;
  double dt_s = 0.1;      // control sample (papers.md P5: 0.02-0.1 s)
  double record_s = 1.0;  // one trajectory row per this much time
};

// What the formation is asked to hold this sample: the desired speed and heading phi*, the shape's
// horizontal scale (form-up and dismiss enlarge it), and each UAV's desired altitude.
struct FormationOrder {
  double speed_mps = 0.0;
  double heading_rad = 0.0;
  double scale = 1.0;
  std::vector<double> altitude_m;  // z_i*
};

class FormationGroup {
 public:
  // `shape`: a slot per UAV (forward, left, up from the reference, m). Throws std::invalid_argument
  // when the lengths differ.
  FormationGroup(std::vector<AutopilotModel> models, std::vector<Vec3> shape, Topology topology,
                 FormationGroupOptions options, double t0_s);

  std::size_t size() const { return models_.size(); }
  double time_s() const { return t_s_; }
  const AutopilotState& state(std::size_t i) const { return states_[i]; }
  bool in_formation(std::size_t i) const { return joined_[i]; }
  const Trajectory& trajectory(std::size_t i) const { return rows_[i]; }
  const std::vector<Vec3>& shape() const { return shape_; }

  // How a launched UAV flies: on its own command (until join()), or under the consensus laws.
  enum class Launch { solo, in_formation };
  // UAV i flies from now with this state (recorded now).
  void launch(std::size_t i, const AutopilotState& state, Launch how);
  void join(std::size_t i) { joined_[i] = true; }
  // UAV i leaves the group (its rows end here).
  void release(std::size_t i);
  bool flying(std::size_t i) const { return flying_[i]; }

  bool anyone_in_formation() const;
  // Mean position of those in formation (P5's reference, the centroid); zero when nobody is.
  Vec3 centroid() const;
  // Largest distance of a UAV in formation from its slot relative to the others' (3-D, m): how far
  // the group is from holding the order's shape.
  double shape_error_m(const FormationOrder& order) const;

  // One control sample: those in formation by the consensus laws towards `order`, each other
  // flying UAV by solo(i) (its own command).
  void step(const FormationOrder& order, const std::function<AutopilotCommand(std::size_t)>& solo);

  // The desired horizontal offsets of the order's shape, turned by its heading (P5 fig. 6).
  std::vector<Vec2> offsets_m(const FormationOrder& order) const;

 private:
  void record(std::size_t i);

  std::vector<AutopilotModel> models_;
  std::vector<AutopilotParams> params_;
  std::vector<Vec3> shape_;
  Topology topology_;
  FormationGroupOptions o_;
  double t_s_;
  std::vector<AutopilotState> states_;
  std::vector<char> flying_, joined_;
  std::vector<Trajectory> rows_;
};

// Steers a group's centroid along a route (P5 sec. 3.1): phi* the bearing from the centroid to the
// current waypoint every sample, z* interpolated along the leg (papers.md P5, eq. 17). A waypoint is
// passed when the centroid comes within the switch distance (the larger of `switch_m` and the
// start of a turn-radius arc into the next leg; fly-over waypoints: `switch_m` only) or is past it
// along the leg.
class RouteSteering {
 public:
  RouteSteering(std::vector<Vec3> route, std::vector<char> fly_over, double turn_radius_m, double switch_m);
  // Advances past the waypoints the centroid has passed; false once past the last.
  bool update(const Vec3& centroid);
  double heading_rad(const Vec3& centroid) const;
  double altitude_m(const Vec3& centroid) const;
  std::size_t next() const { return next_; }
  const std::vector<Vec3>& route() const { return route_; }

 private:
  std::vector<Vec3> route_;
  std::vector<char> fly_over_;
  double radius_m_, switch_m_;
  std::size_t next_ = 1;
};

}  // namespace uavplan
