// What a UAV in the loop knows: tracks of the moving obstacles and UAVs its sensor sees, with
// P1 eq. 7's ground velocity from two observations. Nothing else reaches it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

// P1 eq. 7 with the paper's sign corrected (papers.md P1): relative positions are object -
// UAV, so the object's displacement over dt is the change of the relative position plus the
// UAV's own displacement, D_b = (rel1 - rel0) + (own1 - own0), and V_b = D_b / dt.
Vec3 ground_velocity(const Vec3& rel0_m, const Vec3& rel1_m, const Vec3& own0_m, const Vec3& own1_m, double dt_s);

// An object as the simulation's truth has it at one instant.
struct ObjectState {
  std::string id;
  double radius_m = 0.0;
  bool is_uav = false;
  Vec3 position = Vec3::Zero();
};

struct Track {
  std::size_t object = 0;  // index into the truth snapshot
  std::string id;
  double radius_m = 0.0;
  bool is_uav = false;
  double seen_s = 0.0;               // the latest observation
  Vec3 relative_m = Vec3::Zero();    // object - UAV then
  Vec3 own_m = Vec3::Zero();         // the UAV's position then
  std::optional<Vec3> velocity_mps;  // eq. 7, once seen twice in a row
  // Seen for the first time: it was out of range at the previous refresh, so it moved at least
  // this fast since (range + its radius - its distance now from where the UAV was then) / dt.
  double entered_speed_mps = 0.0;
  // velocity_mps is what the object, a UAV of the same team, was told to fly this period (shared
  // over the team's link), not an estimate: no manoeuvre within the period is unknown.
  bool commanded = false;
  double commanded_slack_m = 0.0;  // how far its path this period strays from that straight line

  Vec3 position() const { return own_m + relative_m; }
};

// A UAV's sensor: its tracks, the last observation of objects that left its range, and where it
// was at its last refresh.
struct Sensor {
  double range_m = 0.0;
  std::vector<Track> tracks;
  std::vector<Track> lost;
  std::optional<Vec3> last_own_m;
  double last_s = 0.0;
};

// Refreshes the tracks from a snapshot: every object (but `self`) whose surface is within range
// of the UAV is observed; an object observed before (at the previous refresh, or before it left
// the range) gets its velocity from the two observations; objects out of range leave the tracks.
void sense(Sensor& sensor, std::span<const ObjectState> truth, std::size_t self, const Vec3& own_m, double t_s);

}  // namespace uavplan
