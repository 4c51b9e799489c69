#include "uavplan/coordination/formation/formation_flight.h"
#include "uavplan/core/tolerances.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "uavplan/coordination/timing.h"

namespace uavplan {
namespace {

// What a UAV is told to fly for the coming period: the straight line from where it is to where
// its route takes it by the period's end, and how far the route strays from that line.
Intent commanded(double t, const FlightState& s, double step_s) {
  if (s.route.empty() || t + kSameTime_s < s.depart_s || s.speed_mps <= 0.0) return {};
  const double v = std::clamp(s.speed_mps, s.spec->speed.min_mps, s.spec->speed.max_mps);
  std::vector<Vec3> pts{s.position};
  double left = v * step_s;
  for (const Vec3& q : s.route) {
    const double len = (q - pts.back()).norm();
    if (len >= left) {
      pts.push_back(pts.back() + (q - pts.back()) * (left / len));
      break;
    }
    left -= len;
    pts.push_back(q);
  }
  const Vec3 end = pts.back(), chord = end - s.position;
  double slack = 0.0;
  for (const Vec3& q : pts) {
    const double f =
        chord.squaredNorm() > 0.0 ? std::clamp((q - s.position).dot(chord) / chord.squaredNorm(), 0.0, 1.0) : 0.0;
    slack = std::max(slack, (q - s.position - f * chord).norm());
  }
  return {Vec3(chord / step_s), slack};
}

}  // namespace

FormationFlight::FormationFlight(const FormationSchedule& schedule, FormationFlightOptions options,
                                 RollingWindow& guard)
    : sched_(schedule), opt_(options), guard_(guard), members_(schedule.slots.size()) {}

// The tracks UAV i guards against: all but those of UAVs that, like it, are in their slots and
// that the schedule keeps apart (more than the separation, with 5 % to spare: within a period a
// UAV flies its path at the period's mean speed, a little off the schedule).
std::vector<Track> FormationFlight::trusted_out(std::size_t i, std::vector<Track> tracks,
                                                std::span<const FlightState> uavs) const {
  std::vector<Track> out;
  const double room = 1.05 * opt_.separation_m + kTimingMargin_m;
  for (Track& k : tracks) {
    std::size_t j = members_.size();
    for (std::size_t m = 0; m < uavs.size() && k.is_uav; ++m)
      if (k.id == uavs[m].spec->id) j = m;
    // Mates share their commands: one that has already decided this period is seen flying what
    // it was told to, not what it flew (a mate turning away from a threat would otherwise be
    // predicted straight on, into the UAV that has not yet had its turn).
    if (j < members_.size() && intent_[j]) {
      k.velocity_mps = intent_[j]->velocity_mps;
      k.commanded = true;
      k.commanded_slack_m = intent_[j]->slack_m;
    }
    // Trusted only when both fly the schedule in step (while re-forming their clocks differ: a
    // laggard catching up may pass where a mate ahead waits).
    if (members_[i].mode != Mode::broken && j < members_.size() && members_[j].mode != Mode::broken &&
        std::abs(period_tau_[j] - period_tau_[i]) <= 1e-6 && members_[j].rate == members_[i].rate) {
      const std::size_t a = sched_.interval(members_[i].tau_s), b = sched_.interval(members_[j].tau_s);
      bool apart = true;
      for (std::size_t q = std::min(a, b); q <= std::max(a, b) + 1 && q + 1 < sched_.knots_s.size(); ++q)
        apart = apart && schedule_gap_m(sched_, i, j, q) > room;
      if (apart) continue;
    }
    out.push_back(std::move(k));
  }
  return out;
}

// One period along its nominal path at its clock rate times `pace` (never past hold_s), the rest
// of the path after it as the route ahead.
void FormationFlight::fly_slot(double t, std::size_t i, FlightState& s, double hold_s, double pace) {
  Member& m = members_[i];
  const double next = std::min({m.tau_s + pace * m.rate * opt_.step_s, sched_.end_s(), std::max(hold_s, m.tau_s)});
  std::vector<Vec3> route = sched_.path(i, m.tau_s, sched_.end_s());
  const double now_m = sched_.length(i, m.tau_s, next);
  route.erase(route.begin());
  s.route = std::move(route);
  // At its goal before the clock's end (its end leg has no length) it hovers there: it has not
  // arrived before the others.
  const bool at_goal = (s.position - sched_.slots[i].back()).norm() <= kSamePoint_m;
  if (s.route.empty() || at_goal) s.route.clear();
  if (at_goal && (next < sched_.end_s() || waiting())) s.route.push_back(s.position);
  s.speed_mps = now_m / opt_.step_s;
  s.depart_s = t;
  s.done = s.route.empty();
  m.tau_s = next;
}

// A broken UAV is back on its path when it is on a segment of it, flying towards that segment's
// end or waiting at the end of what it was given.
void FormationFlight::find_on_path(std::size_t i, const FlightState& s) {
  Member& m = members_[i];
  m.on_path = false;
  const std::vector<Vec3>& p = sched_.slots[i];
  const bool heading = !s.route.empty() && s.route.front() != s.position;  // not hovering
  for (std::size_t k = std::max<std::size_t>(m.knot, 1); k < p.size(); ++k) {
    if (p[k] == p[k - 1] || (heading && p[k] != s.route.front())) continue;
    const Vec3 seg = p[k] - p[k - 1], rel = s.position - p[k - 1];
    const double f = rel.dot(seg) / seg.squaredNorm();
    if (f < -1e-9 || f > 1.0 + 1e-9 || (rel - f * seg).norm() > 1e-6) continue;
    m.on_path = true;
    m.knot = k - 1;
    m.tau_s = sched_.knots_s[k - 1] + std::clamp(f, 0.0, 1.0) * (sched_.knots_s[k] - sched_.knots_s[k - 1]);
    return;
  }
}

// Whether p lies on UAV i's nominal path from where the approach begins to its goal.
bool FormationFlight::on_approach(std::size_t i, const Vec3& p) const {
  const std::vector<Vec3>& path = sched_.slots[i];
  for (std::size_t k = sched_.final_knot; k + 1 < path.size(); ++k) {
    const Vec3 seg = path[k + 1] - path[k];
    const double f = seg.squaredNorm() > 0.0 ? std::clamp((p - path[k]).dot(seg) / seg.squaredNorm(), 0.0, 1.0) : 0.0;
    if ((p - path[k] - f * seg).norm() <= 1e-6 * std::max(1.0, seg.norm())) return true;
  }
  return false;
}

// A UAV out of its slot never finishes alone: its route ends where the others wait for it (the
// approach's start) or, on the approach, where it rejoins its path short of its goal (where it
// left its slot when it would rejoin at the goal itself).
void FormationFlight::clip_route(std::size_t i, FlightState& s) const {
  const Vec3 wait = sched_.slots[i][sched_.final_knot], goal = sched_.slots[i].back();
  const auto it = std::find(s.route.begin(), s.route.end(), wait);
  if (it != s.route.end()) {
    s.route.erase(it + 1, s.route.end());
  } else if (!s.route.empty() && s.route.back() == goal && wait != goal) {
    s.route.pop_back();
    const Vec3 left = sched_.at(i, members_[i].tau_s);
    const bool rejoins = !s.route.empty() && on_approach(i, s.route.back());
    if (!rejoins && (s.position - left).norm() > kSamePoint_m) s.route.push_back(left);
  }
  // Where it waits is its goal when the approach has no length: it hovers there until the others
  // are in their slots (it has not arrived before them).
  if (s.route.empty() && (s.position - goal).norm() <= 1e-6) s.route.push_back(s.position);
  s.done = s.route.empty();
}

// The clock of the UAV furthest on (the one the others re-form on).
double FormationFlight::lead_tau_s() const {
  double hi = -World::kInf;
  for (const Member& m : members_) hi = std::max(hi, m.tau_s);
  return hi;
}

// The re-forming's duration: P1 eq. 9, t = x / (V_max / v) rounded up to whole periods, x the
// clock spread.
double FormationFlight::reform_span_s() const {
  double lo = World::kInf;
  for (const Member& m : members_) lo = std::min(lo, m.tau_s);
  const double hi = lead_tau_s();
  const double catch_up = std::max(1.0, opt_.max_speed_mps / opt_.cruise_mps);
  return std::max(1.0, std::ceil((hi - lo) / catch_up / opt_.step_s - kWholeNumberSlack)) * opt_.step_s;
}

// Whether every pair stays apart while re-forming: each UAV runs its own path at its own clock
// rate, so one catching up may pass over a mate that waits ahead of it (a column's rear UAV flies
// where the one ahead of it was). Sampled 20 times a period, with the room the schedule's
// trust needs; if not, the UAVs fly on as they are and the re-forming waits.
bool FormationFlight::reform_is_clear(double span_s) const {
  const double hi = lead_tau_s();
  const double room = 1.05 * opt_.separation_m + kTimingMargin_m;
  const int samples = static_cast<int>(std::ceil(20.0 * span_s / opt_.step_s));
  for (int k = 0; k <= samples; ++k) {
    const double f = static_cast<double>(k) / samples;
    for (std::size_t i = 0; i < members_.size(); ++i)
      for (std::size_t j = i + 1; j < members_.size(); ++j) {
        const double ti = members_[i].tau_s + f * (hi - members_[i].tau_s);
        const double tj = members_[j].tau_s + f * (hi - members_[j].tau_s);
        if ((sched_.at(i, ti) - sched_.at(j, tj)).norm() <= room) return false;
      }
  }
  return true;
}

// P1 eq. 8-9, N UAVs, on the shared clock: x = max_i tau_i - tau_m (m the furthest behind),
// t = x / (V_max / v) rounded up to whole periods; each UAV's clock runs at (tau_max - tau_i) / t.
void FormationFlight::start_reform(double t, double span_s) {
  const double hi = lead_tau_s();
  for (Member& m : members_) {
    m.mode = Mode::reforming;
    m.rate = (hi - m.tau_s) / span_s;
    m.clear_steps = 0;
  }
  reform_end_s_ = t + span_s;
  ++reforms_;
}

bool FormationFlight::waiting() const {
  return std::any_of(members_.begin(), members_.end(), [](const Member& m) { return m.mode != Mode::formed; });
}

void FormationFlight::control(double t, std::span<FlightState> uavs, std::span<const Sensor> sensors) {
  // Each UAV's plan as the period begins is heard by all (a mate about to stop at its goal is not
  // predicted flying on); those that change it this period are heard again after their turn.
  intent_.clear();
  for (const FlightState& s : uavs) intent_.push_back(commanded(t, s, opt_.step_s));
  period_tau_.clear();
  for (const Member& m : members_) period_tau_.push_back(m.tau_s);
  if (reform_end_s_ >= 0.0 && t + kSameTime_s >= reform_end_s_) {  // re-formed: w = 0 again
    for (Member& m : members_)
      if (m.mode == Mode::reforming) m.mode = Mode::formed, m.rate = 1.0;
    for (FormationBreak& b : breaks_)
      if (b.to_s < 0.0 && members_[b.uav].mode == Mode::formed) b.to_s = t;
    reform_end_s_ = -1.0;
  }
  // Re-form once every UAV out of its slot is back on its path and has been clear long enough.
  bool any_broken = false, ready = reform_end_s_ < 0.0;
  for (std::size_t i = 0; i < uavs.size(); ++i) {
    if (members_[i].mode != Mode::broken) continue;
    any_broken = true;
    find_on_path(i, uavs[i]);
    ready = ready && members_[i].on_path && members_[i].clear_steps >= opt_.reform_after_steps;
  }
  if (any_broken && ready) {
    const double span_s = reform_span_s();
    if (reform_is_clear(span_s)) {
      start_reform(t, span_s);
      any_broken = false;
    }
  }
  // While any UAV is out of its slot the formation slows and waits for it where the approach
  // begins: the UAVs reach their goals together, in shape.
  const double hold_s = any_broken ? sched_.knots_s[sched_.final_knot] : sched_.end_s();
  const double pace = any_broken ? opt_.slow_pace : 1.0;
  for (std::size_t i = 0; i < uavs.size(); ++i) {
    Member& m = members_[i];
    FlightState& s = uavs[i];
    const std::vector<Track> tracks = trusted_out(i, sensors[i].tracks, uavs);
    if (m.mode == Mode::broken) {
      // Stopped short of where it waits (its local route ended off its path, or a re-forming was
      // put off): on along its path from where it was last on it.
      if (s.route.empty() && (s.position - sched_.slots[i][sched_.final_knot]).norm() > 1e-6)
        s.route = sched_.path(i, m.tau_s, sched_.end_s());
      s.speed_mps = s.spec->speed.cruise_mps;
      m.clear_steps = guard_.guard(t, i, s, tracks) ? 0 : m.clear_steps + 1;
      clip_route(i, s);
      intent_[i] = commanded(t, s, opt_.step_s);
      continue;
    }
    const double tau_before = m.tau_s;
    if (m.mode == Mode::formed && formed_s_ >= 0.0)
      worst_slot_error_m_ = std::max(worst_slot_error_m_, (s.position - sched_.at(i, m.tau_s)).norm());
    fly_slot(t, i, s, hold_s, m.mode == Mode::formed ? pace : 1.0);
    if (formed_s_ < 0.0 && m.tau_s >= sched_.knots_s[sched_.form_up_knot]) formed_s_ = t + opt_.step_s;
    intent_[i] = commanded(t, s, opt_.step_s);
    if (!guard_.threatened(t, i, s, tracks)) continue;
    // Leaves its slot (w = 1), flying its own way back onto its path at cruise speed, around
    // every other UAV as well.
    members_[i].mode = Mode::broken;
    guard_.guard(t, i, s, trusted_out(i, sensors[i].tracks, uavs));
    const bool open = std::any_of(breaks_.begin(), breaks_.end(),
                                  [&](const FormationBreak& b) { return b.uav == i && b.to_s < 0.0; });
    if (!open) breaks_.push_back({i, t, -1.0});
    m.mode = Mode::broken;
    m.tau_s = tau_before;
    m.knot = sched_.interval(tau_before);
    m.clear_steps = 0;
    if (s.speed_mps > 0.0) s.speed_mps = s.spec->speed.cruise_mps;
    clip_route(i, s);
    intent_[i] = commanded(t, s, opt_.step_s);
  }
}

}  // namespace uavplan
