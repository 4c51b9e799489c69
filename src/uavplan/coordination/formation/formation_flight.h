// P1's cooperative avoidance and re-forming (sec. 2.4) as a closed-loop controller. Each period T
// every UAV in its slot flies its nominal path one period on (formation_schedule.h). Its route
// ahead is guarded by the rolling window (rolling_window.h) against what its sensor tracks; UAVs
// in their slots do not guard against each other where the schedule keeps them apart. When the
// guard must act the UAV leaves its slot (flag w = 1): it replans locally around the threat back
// onto its own path, treating every other UAV as a moving object (and is one to them). Back on
// its path and clear for `reform_after_steps` periods, the formation re-forms by P1 eq. 8-9 in
// N-UAV form, on the shared clock: the UAV furthest behind catches up at V_max while each other
// UAV flies just fast enough to be in its slot when it arrives (the foremost hovers), and from
// then on all fly the schedule together. While a UAV is out of its slot the others slow down
// (`slow_pace`) and wait for it where the approach to the goals begins (never at their goals),
// so that all arrive together, in shape.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "uavplan/coordination/formation/formation_schedule.h"
#include "uavplan/coordination/routes/rolling_window.h"

namespace uavplan {

struct FormationFlightOptions {
  double step_s = 1.0;
  double separation_m = 0.0;
  int reform_after_steps = 5;
  double max_speed_mps = 0.0;  // V_max: the slowest UAV's top speed
  double cruise_mps = 0.0;     // the schedule's speed
  // The formation's pace while a UAV is out of its slot (a fraction of cruise_mps): half, or the
  // slowest pace its UAVs can fly, so that the one out of its slot has less to catch up.
  double slow_pace = 0.5;
};

// A UAV's command for the coming period as its mates hear it: a straight line at a velocity, and
// how far its route strays from that line within the period.
struct Intent {
  Vec3 velocity_mps = Vec3::Zero();
  double slack_m = 0.0;
};

struct FormationBreak {
  std::size_t uav = 0;
  double from_s = 0.0, to_s = -1.0;  // to_s < 0: not re-formed
};

class FormationFlight final : public FlightController {
 public:
  FormationFlight(const FormationSchedule& schedule, FormationFlightOptions options, RollingWindow& guard);
  void control(double t_s, std::span<FlightState> uavs, std::span<const Sensor> sensors) override;
  // Until every UAV is back in its slot: one waiting out of its slot at the end leg has not arrived.
  bool waiting() const override;
  const std::vector<FormationBreak>& breaks() const { return breaks_; }
  int reforms() const { return reforms_; }
  double formed_s() const { return formed_s_; }
  // The farthest a UAV in its slot was from it at a period's start (after the form-up).
  double worst_slot_error_m() const { return worst_slot_error_m_; }  // when the formation was first formed (-1: never)

 private:
  enum class Mode { formed, broken, reforming };
  struct Member {
    Mode mode = Mode::formed;
    double tau_s = 0.0;  // its place on the shared clock
    double rate = 1.0;   // clock seconds per second while re-forming
    int clear_steps = 0;
    bool on_path = false;  // a broken UAV back on its own path (tau_s then valid)
    std::size_t knot = 0;  // the knot its path position was last found before
  };
  std::vector<Track> trusted_out(std::size_t i, std::vector<Track> tracks, std::span<const FlightState> uavs) const;
  void fly_slot(double t_s, std::size_t i, FlightState& s, double hold_s, double pace);
  bool on_approach(std::size_t i, const Vec3& p) const;
  void find_on_path(std::size_t i, const FlightState& s);
  void clip_route(std::size_t i, FlightState& s) const;
  double lead_tau_s() const;
  double reform_span_s() const;
  bool reform_is_clear(double span_s) const;
  void start_reform(double t_s, double span_s);
  const FormationSchedule& sched_;
  FormationFlightOptions opt_;
  RollingWindow& guard_;
  std::vector<Member> members_;
  std::vector<FormationBreak> breaks_;
  std::vector<double> period_tau_;             // the clocks as the period began
  std::vector<std::optional<Intent>> intent_;  // this period's commands of the UAVs that have had their turn
  double reform_end_s_ = -1.0;
  double formed_s_ = -1.0;
  double worst_slot_error_m_ = 0.0;
  int reforms_ = 0;
};

}  // namespace uavplan
