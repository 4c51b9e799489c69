#include "uavplan/planning/pso/pso_mpc.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "uavplan/planning/segment_rule.h"

namespace uavplan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }
double bearing(const Vec3& from, const Vec3& to) { return std::atan2(to.y() - from.y(), to.x() - from.x()); }

// The obstacles a step's candidates can reach: those whose bounding boxes lie within the longest
// segment a candidate checks (its step with the prediction, or the last segment into the
// target) of the step's start. Each of the swarm's thousands of candidates is checked against
// these alone, exactly; a world with terrain asks the world.
struct Nearby {
  std::vector<const Obstacle*> obstacles;
  bool whole_world = false;
};

// What one leg's steps share.
struct LegPlanner {
  const World& world;
  const SegmentRule& rule;
  const PsoMpcOptions& o;
  double l, dh_max, turn_max;

  Nearby nearby(const Vec3& p, int prediction_steps) const {
    Nearby n;
    if (world.terrain()) {
      n.whole_world = true;
      return n;
    }
    const double reach = std::max(1.0 + prediction_steps, 4.0) * std::hypot(l, dh_max) + 2.0 * rule.inflation_m() + 1.0;
    world.visit_near(p, reach, [&](const Obstacle& ob) { n.obstacles.push_back(&ob); });
    return n;
  }

  bool clear(const Vec3& a, const Vec3& b, const Nearby& n) const {
    const double r = rule.inflation_m();
    if (n.whole_world) return !world.segment_collides(a, b, r);
    for (const Obstacle* ob : n.obstacles)
      if (segment_distance(*ob, a, b, r) < r) return false;
    return true;
  }

  // The rule for a segment from the step's start (or within its reach).
  bool allowed(const Vec3& a, const Vec3& b, const Nearby* n) const {
    return n ? rule.limits_ok(a, b) && clear(a, b, *n) : rule(a, b);
  }

  // The prediction Q -> SP clear of the obstacles, cut where it leaves the bounds and kept within
  // the airspace's heights (papers.md P5: SP may lie outside; only the no-fly zones count).
  bool prediction_clear(const Vec3& q, const Vec3& sp, const Nearby& n) const {
    const Aabb& b = world.bounds();
    double t = 1.0;
    for (int k = 0; k < 2; ++k) {
      const double d = sp[k] - q[k];
      if (d > 0.0 && sp[k] > b.max[k]) t = std::min(t, (b.max[k] - q[k]) / d);
      if (d < 0.0 && sp[k] < b.min[k]) t = std::min(t, (b.min[k] - q[k]) / d);
    }
    Vec3 end = q + std::max(t, 0.0) * (sp - q);
    end.z() = std::clamp(end.z(), b.min.z() + rule.inflation_m(),
                         std::max(b.min.z() + rule.inflation_m(), rule.ceiling_m() - rule.inflation_m()));
    return clear(q, end, n);
  }

  // The last segment from x into t (and, with an entry heading, onto the fixed segment) within
  // the limits: eq. 6 and eq. 10.
  bool closes(const Vec3& x, const std::optional<Vec3>& in, const Vec3& t, const std::optional<double>& entry,
              const Nearby* n = nullptr) const {
    const Vec3 last = t - x;
    if (last.norm() <= kSamePoint_m) return true;
    if (in && !turn_within(*in, last, turn_max + kAngleTolerance_rad)) return false;
    if (std::abs(t.z() - x.z()) > dh_max + 1e-9 || !allowed(x, t, n)) return false;
    return !entry || turn_within(last, heading_vector(*entry), turn_max + kAngleTolerance_rad);
  }

  // Eqs. 5-12 for the candidate U = (dphi, dh) from p (heading psi, arriving along `in`).
  double cost(std::span<const double> u, const Vec3& p, double psi, const std::optional<Vec3>& in, const Vec3& t,
              const std::optional<double>& entry, int prediction_steps, const Nearby& n) const {
    const double psi_c = psi + u[0], d = (p - t).norm();
    const Vec3 q = p + Vec3(l * std::cos(psi_c), l * std::sin(psi_c), u[1]);
    const Vec3 seg = q - p;
    if (!allowed(p, q, &n)) return kInf;
    if (in && !turn_within(*in, seg, turn_max + kAngleTolerance_rad)) return kInf;
    if (d < 3.0 * l && !closes(q, seg, t, entry, &n)) return kInf;  // eq. 6 (and 10): hard near the end
    Vec3 e = q;
    if (prediction_steps > 0 && d > o.d_t_l * l) {
      const Vec3 sp = p + (1.0 + prediction_steps) * seg;
      if (!prediction_clear(q, sp, n)) return kInf;
      e = sp;
      e.z() = std::clamp(e.z(), world.bounds().min.z(), world.bounds().max.z());  // for the cost only
    }
    double j = (e - t).norm() + o.alpha * std::abs(e.z() - t.z());
    if (d <= o.d_tar_l * l) {
      const double term = entry ? std::abs(wrap(*entry - bearing(e, t))) : std::abs(wrap(bearing(e, t) - psi_c));
      j += (entry ? o.gamma_per_l : o.beta_per_l) * l * rad_to_deg(term);
    }
    return j;
  }
};

}  // namespace

PsoMpcOptions PsoMpcOptions::from_params(const Params& params) {
  ParamReader r(params, "pso_mpc");
  PsoMpcOptions o = read(r);
  r.finish();
  return o;
}

PsoMpcOptions PsoMpcOptions::read(ParamReader& r) {
  PsoMpcOptions o;
  o.step_m = r.number("step", 0.0, 0.0, 1e7, "l, the step to the next waypoint, m; 0: derived from the distance");
  o.max_turn_deg = r.number("max_turn_deg", o.max_turn_deg, 1.0, 90.0,
                            "dphi_max, deg (P5 Table 1: 30); never more than the UAV's turn limit");
  o.max_dh_m = r.number("max_dh", 0.0, 0.0, 1e6, "dh_max, the climb per step, m; 0: from the UAV's climb limit");
  o.alpha = r.number("alpha", o.alpha, 0.0, 1e6, "alpha, the terminal term's weight (P5 Table 1)");
  o.beta_per_l = r.number("beta_per_l", o.beta_per_l, 0.0, 1e3, "beta per l, the distance-to-target weight");
  o.gamma_per_l = r.number("gamma_per_l", o.gamma_per_l, 0.0, 1e3, "gamma per l, the entry-heading weight");
  o.prediction_steps =
      r.integer("prediction", o.prediction_steps, 0, 100, "the look-ahead steps (P5: 11; 0: J0, eq. 4)");
  o.pso.particles = r.integer("particles", o.pso.particles, 2, 10000, "the swarm's particles");
  o.pso.iterations = r.integer("iterations", o.pso.iterations, 0, 100000, "the swarm's iterations per step");
  o.pso.stall_iterations = r.integer("stall", o.pso.stall_iterations, 0, 100000,
                                     "iterations without improvement before a step ends (0: never)");
  o.pso.infeasible_iterations = r.integer("give_up", o.pso.infeasible_iterations, 0, 100000,
                                          "iterations without a feasible particle before a step fails (0: never)");
  return o;
}

namespace {

constexpr const char* kStoppedWhy = "stopped before the route was complete";

// The best of a 13 x 3 grid over the box (turns 1/12 of the range apart; level, up and down),
// if any is feasible.
template <class F>
std::optional<std::array<double, 2>> coarse_best(const F& f, const std::array<double, 2>& lo,
                                                 const std::array<double, 2>& hi) {
  std::optional<std::array<double, 2>> best;
  double best_f = kInf;
  for (int i = 0; i <= 12; ++i)
    for (int k = 0; k <= 2; ++k) {
      const std::array<double, 2> x{lo[0] + (hi[0] - lo[0]) * i / 12.0, lo[1] + (hi[1] - lo[1]) * k / 2.0};
      const double v = f(std::span<const double>(x));
      if (v < best_f) best_f = v, best = x;
    }
  return best;
}

// How a leg ended: Reason::none (flown), stopped, or no_route with why (": ..." after the leg's
// name).
struct LegOutcome {
  Reason reason = Reason::none;
  std::string why;
};

// One leg of P5's multi-step planning, from route.back() (arriving along `in`) to `task`: a PSO
// per waypoint, backing up from dead ends. Flown, it appends the leg's waypoints to `route` and
// sets `in`; else it leaves both as they were.
class LegFlight {
 public:
  LegFlight(const LegPlanner& lp, const Vec3& task, const std::optional<double>& entry, const Rng& base,
            std::uint64_t salt, const StopCondition& stop)
      : lp_(lp), task_(task), entry_(entry), base_(base), salt_(salt), stop_(stop) {}

  LegOutcome fly(std::vector<Vec3>& route_io, std::optional<Vec3>& in_io, PlanStats& stats);

 private:
  // The leg's states before each step, with the turns tried from each that led to dead ends:
  // where no waypoint is feasible it backs up a step and turns another way (at most
  // kMaxBacktracks times a leg; P5 re-runs the swarm, which cannot leave a dead end: that only
  // where there is no step to back up).
  struct Before {
    Vec3 p;
    double psi;
    std::optional<Vec3> in;
    std::size_t route_size;
    std::vector<double> dead;  // turns (dphi) that led to dead ends
    double chosen = 0.0;
  };
  static constexpr int kMaxBacktracks = 200;

  PsoResult best_step(int step);
  bool back_up();
  void take(const PsoResult& best);

  const LegPlanner& lp_;
  Vec3 task_;
  std::optional<double> entry_;
  const Rng& base_;
  std::uint64_t salt_;
  const StopCondition& stop_;
  Vec3 target_, p_;
  double psi_ = 0.0;
  std::vector<Vec3> route_;
  std::optional<Vec3> in_;
  std::vector<Before> history_;
  std::vector<double> dead_here_;
  int backtracks_ = 0;
};

// The swarm's best [dphi, dh] from here; f = inf where none is feasible. A coarse look over the
// turns first: where every heading's look-ahead is blocked, look nearer before the swarm is asked
// (a blocked swarm spends 20 iterations finding nothing).
PsoResult LegFlight::best_step(int step) {
  const double turn_max = lp_.turn_max, dh_max = lp_.dh_max;
  const PsoMpcOptions& options = lp_.o;
  const double near = 0.25 * turn_max;
  int prediction = options.prediction_steps;
  const Nearby nearby = lp_.nearby(p_, prediction);
  const auto f = [&](std::span<const double> x) {
    for (const double d : dead_here_)
      if (std::abs(x[0] - d) < near) return kInf;
    return lp_.cost(x, p_, psi_, in_, target_, entry_, prediction, nearby);
  };
  const std::array<double, 2> lo{-turn_max, -dh_max}, hi{turn_max, dh_max};
  std::array<double, 6> seeds{0.0,
                              0.0,
                              std::clamp(wrap(bearing(p_, target_) - psi_), -turn_max, turn_max),
                              std::clamp(target_.z() - p_.z(), -dh_max, dh_max),
                              0.0,
                              0.0};
  while (prediction > 0) {
    const std::optional<std::array<double, 2>> open = coarse_best(f, lo, hi);
    if (open) {
      seeds[4] = (*open)[0], seeds[5] = (*open)[1];
      break;
    }
    prediction /= 2;
  }
  Rng rng = base_.split(salt_ + static_cast<std::uint64_t>(step));
  PsoResult best = pso_minimize(f, lo, hi, options.pso, rng, seeds);
  // Every candidate's straight look-ahead blocked (a no-fly zone ahead closer than the
  // prediction reaches, a turn of 30 deg per step cannot clear it): look half as far ahead.
  while (best.f == kInf && prediction > 0) {
    prediction /= 2;
    const PsoResult shorter = pso_minimize(f, lo, hi, options.pso, rng, seeds);
    best.evaluations += shorter.evaluations;
    best.f = shorter.f, best.x = shorter.x;
  }
  if (best.f == kInf && history_.empty()) {  // once more, with a swarm twice as large (papers.md P5)
    PsoOptions wider = options.pso;
    wider.particles *= 2;
    wider.iterations *= 2;
    const PsoResult again = pso_minimize(f, lo, hi, wider, rng, seeds);
    best.evaluations += again.evaluations;
    best.f = again.f, best.x = again.x;
  }
  return best;
}

// Back one step, the turn taken from there marked dead; false when there is none to back up
// (or the leg has backed up kMaxBacktracks times).
bool LegFlight::back_up() {
  if (history_.empty() || backtracks_ >= kMaxBacktracks) return false;
  ++backtracks_;
  Before b = std::move(history_.back());
  history_.pop_back();
  b.dead.push_back(b.chosen);
  p_ = b.p, psi_ = b.psi, in_ = b.in;
  route_.resize(b.route_size);
  dead_here_ = std::move(b.dead);
  return true;
}

void LegFlight::take(const PsoResult& best) {
  history_.push_back({p_, psi_, in_, route_.size(), std::move(dead_here_), best.x[0]});
  dead_here_.clear();
  psi_ += best.x[0];
  const Vec3 q = p_ + Vec3(lp_.l * std::cos(psi_), lp_.l * std::sin(psi_), best.x[1]);
  in_ = q - p_;
  route_.push_back(q);
  p_ = q;
}

LegOutcome LegFlight::fly(std::vector<Vec3>& route_io, std::optional<Vec3>& in_io, PlanStats& stats) {
  const double l = lp_.l;
  route_ = route_io;
  in_ = in_io;
  target_ = task_;
  if (entry_) {  // eq. 10: the fixed final segment, one step l long at the task's height
    target_ = task_ - l * heading_vector(*entry_);
    if (!lp_.rule.point_ok(target_) || !lp_.rule(target_, task_))
      return {Reason::no_route, ": the fixed segment into the entry heading is blocked"};
  }
  p_ = route_.back();
  psi_ = in_ ? std::atan2(in_->y(), in_->x()) : bearing(p_, target_);
  const int cap = static_cast<int>(10.0 * (p_ - target_).norm() / l) + 20;
  bool arrived = (p_ - target_).norm() <= kSamePoint_m;
  for (int step = 0; static_cast<int>(history_.size()) < cap && !arrived; ++step) {  // backtracks are bounded
    if (stop_.should_stop()) return {Reason::stopped, kStoppedWhy};
    if ((p_ - target_).norm() < 2.0 * l && lp_.closes(p_, in_, target_, entry_)) {  // the target: the last waypoint
      in_ = target_ - p_;
      route_.push_back(target_);
      arrived = true;
      break;
    }
    const PsoResult best = best_step(step);
    stats.nodes_expanded += static_cast<std::uint64_t>(best.evaluations);
    if (best.f != kInf) {
      take(best);
      continue;
    }
    if (!back_up()) {
      const std::string buf = strf(": no feasible waypoint %g m on from (%.1f, %.1f, %.1f)", l, p_.x(), p_.y(), p_.z());
      return {Reason::no_route, buf};
    }
  }
  if (!arrived)
    return {Reason::no_route, ": not at its target within " + std::to_string(cap) + " steps of " +
                                  std::to_string(static_cast<int>(l)) + " m"};
  if (entry_) {
    in_ = task_ - target_;
    route_.push_back(task_);
  }
  route_io = std::move(route_);
  in_io = in_;
  return {};
}

}  // namespace

PsoSteps pso_steps(const PsoMpcOptions& o, const UavSpec& uav, const World& world) {
  PsoSteps st;
  st.max_turn_rad = std::min(deg_to_rad(o.max_turn_deg), uav.max_turn_rad);
  const double side = std::max(world.bounds().extent().x(), world.bounds().extent().y());
  st.step_m = o.step_m > 0.0 ? o.step_m : side >= 200000.0 ? 5000.0 : side / 40.0;
  if (o.step_m <= 0.0 && uav.max_turn_rate_rad_s)  // long enough for the vehicle to turn dphi_max between waypoints
    st.step_m =
        std::max(st.step_m, 2.0 * uav.speed.cruise_mps / *uav.max_turn_rate_rad_s * std::sin(0.5 * st.max_turn_rad));
  double climb = uav.max_climb_rad < kPi / 2 - kUnlimitedAngleSlack_rad ? uav.max_climb_rad : std::atan(300.0 / 5000.0);
  if (uav.max_climb_rate_mps) climb = std::min(climb, std::atan(*uav.max_climb_rate_mps / uav.speed.cruise_mps));
  st.max_dh_m = o.max_dh_m > 0.0 ? o.max_dh_m : st.step_m * std::tan(climb);
  return st;
}

namespace {

// P5's multi-step planning with a given look-ahead (prediction steps).
PlanResult plan_multi_step(const Problem& pb, const World& world, const StopCondition& stop,
                           const PsoMpcOptions& options) {
  PlanResult res;
  const PsoSteps steps = pso_steps(options, pb.uav, world);
  const double l = steps.step_m, turn_max = steps.max_turn_rad, dh_max = steps.max_dh_m;
  // A UAV flown through its model turns on arcs of radius R that cut each corner by up to
  // R (1 / cos(dphi_max / 2) - 1): the no-fly zones are kept that much further off.
  UavSpec u = pb.uav;
  if (u.model && u.max_turn_rate_rad_s)
    u.radius_m += u.speed.cruise_mps / *u.max_turn_rate_rad_s * (1.0 / std::cos(0.5 * turn_max) - 1.0);
  // The same overshoot, and the body, kept inside the bounds' sides (never past a fixed point).
  std::vector<Vec3> fixed = pb.via;
  fixed.push_back(u.start);
  fixed.push_back(pb.goal);
  double edge_m = u.radius_m;
  const Aabb& box = world.bounds();
  for (const Vec3& f : fixed)
    for (int k = 0; k < 2; ++k) edge_m = std::min({edge_m, f[k] - box.min[k], box.max[k] - f[k]});
  const SegmentRule rule = SegmentRule(world, u).with_edge_margin(edge_m);
  // A leg whose waypoints l apart cannot go on (a start heading into a nearby corner, a dead end
  // the backtracking does not leave, a target it circles) is flown again with steps half as
  // long, never shorter than the vehicle turns dphi_max in (its turn circle's chord).
  double l_min = 0.5 * l;
  if (u.model && u.max_turn_rate_rad_s)
    l_min = std::max(l_min, 2.0 * u.speed.cruise_mps / *u.max_turn_rate_rad_s * std::sin(0.5 * turn_max));
  std::vector<Vec3> route{u.start};
  std::optional<Vec3> in;
  if (u.heading_rad) in = heading_vector(*u.heading_rad);
  std::vector<Vec3> stops = pb.via;
  stops.push_back(pb.goal);
  const Rng base(pb.seed);
  for (std::size_t leg = 0; leg < stops.size(); ++leg) {
    const std::optional<double> entry =
        leg < pb.via_entry_heading_rad.size() && leg < pb.via.size() ? pb.via_entry_heading_rad[leg] : std::nullopt;
    LegOutcome leg_end;
    for (const double lt : {l, l_min}) {
      const LegPlanner leg_planner{world, rule, options, lt, dh_max * lt / l, turn_max};
      leg_end = LegFlight(leg_planner, stops[leg], entry, base, leg * 1000003u + (lt < l ? 500000u : 0u), stop)
                    .fly(route, in, res.stats);
      if (leg_end.reason == Reason::none || leg_end.reason == Reason::stopped || l_min >= l) break;
    }
    if (leg_end.reason != Reason::none) {
      res.message = leg_end.reason == Reason::stopped ? leg_end.why : leg_name(leg, stops.size() + 1) + leg_end.why;
      res.reason = leg_end.reason;
      return res;
    }
  }
  res.status = Status::solved;
  res.route.waypoints = std::move(route);
  res.route.waypoints.erase(std::unique(res.route.waypoints.begin(), res.route.waypoints.end()),
                            res.route.waypoints.end());
  return res;
}

}  // namespace

// The look-ahead's straight ray is blind to gaps narrower than itself: a ray of 12 steps that
// meets a no-fly zone rules its heading out, and the route may go round a whole group of them.
// Where P5's look-ahead fails, or its route is more than kLongRoute times the straight lines
// through the stops, the route is planned again looking half as far ahead and the shorter kept
// (bench p5-coarse: without it three of 30 random worlds came out 15-63 % longer than A*'s).
PlanResult PsoMpcPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  constexpr double kLongRoute = 1.2;
  PlanResult first = plan_multi_step(pb, world, stop, options_);
  Route straight{{pb.uav.start}};
  straight.waypoints.insert(straight.waypoints.end(), pb.via.begin(), pb.via.end());
  straight.waypoints.push_back(pb.goal);
  const bool solved = first.status == Status::solved;
  if (options_.prediction_steps < 2 || stop.should_stop() ||
      (solved && first.route.length_m() <= kLongRoute * straight.length_m()))
    return first;
  PsoMpcOptions nearer = options_;
  nearer.prediction_steps /= 2;
  PlanResult second = plan_multi_step(pb, world, stop, nearer);
  const bool second_better = second.status == Status::solved
                                 ? !solved || second.route.length_m() < first.route.length_m()
                                 : !solved && second.reason == Reason::stopped;
  PlanResult& kept = second_better ? second : first;
  kept.stats.nodes_expanded = first.stats.nodes_expanded + second.stats.nodes_expanded;
  return std::move(kept);
}

}  // namespace uavplan
