// P1's local layer (sec. 2.3, papers.md P1): every period T each UAV inflates every object its
// sensor tracks to a sphere (a disc in a flat world) of radius T |V_b| + the object's radius +
// its own (for another UAV: the separation, at least the two radii), V_b from eq. 7. When one
// touches its route ahead inside the window, it replans with the local RRT from where it is to
// a rejoin point on the route: the first point past the last touch plus one UAV step that is
// clear when the UAV gets there, and never past the next via point ahead (a detour passes
// through it).
//
// Our additions, where the paper is silent or its disc is not enough:
//  - the disc is carried along V_b: the route ahead is checked against where the disc will be
//    when the UAV gets there (exact in time), which is the paper's disc for a still obstacle and
//    catches an obstacle overtaking from behind or meeting the UAV further along;
//  - an object seen once has no V_b yet: its disc grows by T times the UAV's own top speed;
//  - a disc the UAV is already inside is shrunk to its present distance (it may not come closer),
//    and when that leaves no way, to the bodies plus a quarter of the T |V_b| margin;
//  - when the RRT still finds nothing, a UAV that may hover (min speed 0) waits where it is if
//    that is clear for the window's time, else it escapes: of the straight flights at top speed
//    (24 headings, three pitches in 3-D, within its turn and climb limits) or hovering, the one
//    whose closest predicted approach to any tracked body over five periods is largest, for one
//    period, then it replans;
//  - a UAV at its goal keeps watch: when a disc would reach it there it escapes and comes back;
//  - right of way: of two UAVs in the loop, the later in the scenario gives way (the earlier keeps
//    only their bodies apart), as UAVs flying fixed trajectories have it over all in the loop.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "uavplan/planning/sampling/rrt.h"
#include "uavplan/simulation/closed_loop.h"

namespace uavplan {

struct RollingWindowOptions {
  double step_s = 1.0;        // T
  double separation_m = 0.0;  // between UAVs (the mission's)
  RrtOptions local = RrtOptions::improved();
  std::uint64_t seed = 1;
  StopCondition stop;
  // Points a route passes in order (a route mission's via points, a sortie's start and goal on
  // its way from and back to home): a local route rejoins the route before the next one ahead on
  // it, or at it, never past it.
  std::vector<Vec3> via_points;
};

struct ReplanEvent {
  double t_s = 0.0;
  std::string object;                // the track whose disc touched the route (first found)
  Vec3 velocity_mps = Vec3::Zero();  // its V_b as the UAV estimated it
  enum class Outcome { replanned, held, escaped, none } outcome = Outcome::none;
};

struct RollingWindowLog {
  std::vector<ReplanEvent> events;
  int replans = 0;  // RRT replans that succeeded
  int holds = 0, escapes = 0;
  double local_ms = 0.0;  // time spent in the local RRT
  std::string trouble;    // the last situation with no clear way out, for failure messages
};

// A tracked object as the UAV plans around it: the disc (see above) and the distance at which
// it would touch it (the radii, or the separation for another UAV).
struct ThreatDisc {
  MovingKeepOut disc;
  double body_m = 0.0;
  bool gives_way = false;  // a UAV that plans around this one (a body only)
};

// The discs of a UAV's tracks at time t_s, one per track in order; those marked in bodies_only
// are just the bodies, moving with their V_b.
std::vector<ThreatDisc> threat_discs(const UavSpec& uav, const std::vector<Track>& tracks, double t_s, double step_s,
                                     double separation_m, std::span<const char> bodies_only = {});

class RollingWindow final : public FlightController {
 public:
  // windows_m: per UAV, the length of route ahead it checks (its sensor range by default); ids:
  // the UAVs in the loop in priority order (a UAV gives way to the ones before it).
  RollingWindow(const World& world, RollingWindowOptions options, std::vector<double> windows_m,
                const std::vector<std::string>& ids);
  // Every UAV at its cruise speed, guarded.
  void control(double t_s, std::span<FlightState> uavs, std::span<const Sensor> sensors) override;
  // UAV i's route ahead against its tracks' discs, at the speed it was given: true when the route
  // was touched (it replanned, held or escaped) or, at its goal, it had to escape.
  bool guard(double t_s, std::size_t i, FlightState& s, const std::vector<Track>& tracks);
  // Whether guard() would act (nothing changed).
  bool threatened(double t_s, std::size_t i, const FlightState& s, const std::vector<Track>& tracks) const;
  const RollingWindowLog& log(std::size_t uav) const { return logs_[uav]; }

 private:
  std::vector<ThreatDisc> discs_for(double t_s, std::size_t i, const FlightState& s,
                                    const std::vector<Track>& tracks) const;
  bool replan(double t_s, std::size_t i, FlightState& s, const std::vector<ThreatDisc>& threats, const Vec3& bias_mps,
              std::string& why);
  bool clear_to_stay(double t_s, std::size_t i, const FlightState& s, const std::vector<ThreatDisc>& threats) const;
  bool escape(double t_s, FlightState& s, const std::vector<ThreatDisc>& threats) const;
  const World& world_;
  RollingWindowOptions opt_;
  std::vector<RollingWindowLog> logs_;
  std::vector<double> window_m_;
  std::map<std::string, std::size_t> priority_;  // loop UAV id -> its place (earlier: right of way)
};

}  // namespace uavplan
