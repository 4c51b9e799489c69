#include "uavplan/planning/sampling/rrt.h"
#include "uavplan/core/tolerances.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

#include "uavplan/core/geometry.h"
#include "uavplan/core/rng.h"
#include "uavplan/core/text.h"
#include "uavplan/planning/sampling/chaotic_sampler.h"
#include "uavplan/planning/sampling/rrt_tree.h"
#include "uavplan/planning/smoothing/waypoint_pruning.h"

namespace uavplan {

RrtOptions RrtOptions::common() { return RrtOptions{}; }

RrtOptions RrtOptions::improved() {
  RrtOptions o;
  o.chaotic = true;
  o.lambda = 1.0;
  o.prune = true;
  o.shortcut = true;
  return o;
}

RrtOptions RrtOptions::from_params(const Params& params, RrtVariant variant) {
  ParamReader r(params, variant == RrtVariant::improved ? "improved_rrt" : "rrt");
  RrtOptions o = read(r, variant);
  r.finish();
  return o;
}

RrtOptions RrtOptions::read(ParamReader& r, RrtVariant variant) {
  const bool improved = variant == RrtVariant::improved;
  RrtOptions o = improved ? RrtOptions::improved() : RrtOptions::common();
  o.step_m = r.number("step_m", o.step_m, 0.0, 1e9,
                      "epsilon, the growth step, m; 0: P1's 2 m, or diagonal / 50 in worlds over 100 m");
  o.goal_bias = r.number("goal_bias", o.goal_bias, 0.0, 1.0, "p_s, the probability of growing toward the goal");
  o.max_nodes =
      r.integer("max_nodes", o.max_nodes, 2, 10'000'000, "the tree's nodes before giving up (P1: 5000 per replan)");
  if (improved) {
    o.chaotic = r.boolean("chaotic", o.chaotic, "logistic-map samples (improved)");
    o.arcsine_uniform = r.boolean("arcsine_uniform", o.arcsine_uniform, "the chaos transformed to uniform samples");
    o.lambda = r.number("lambda", o.lambda, -100.0, 100.0,
                        "the growth bias toward the obstacle's velocity V_b / cruise (improved: 1)");
    o.prune = r.boolean("prune", o.prune, "P1's 5-look-ahead removal of redundant waypoints");
    o.lookahead = r.integer("lookahead", o.lookahead, 1, 1000, "the pruning's look-ahead");
    o.shortcut = r.boolean("shortcut", o.shortcut, "line-of-sight shortcuts after pruning");
  }
  return o;
}

double RrtOptions::step_in(const Aabb& bounds) const {
  if (step_m > 0.0) return step_m;
  // P1's 2 m suits its 40 m x 45 m window; a larger world would need thousands of steps to cross.
  return std::max(2.0, bounds.extent().norm() / 50.0);
}

double keep_out_distance(const MovingKeepOut& k, const Vec3& a, double t_a_s, const Vec3& b, double t_b_s) {
  return point_segment_distance(Vec3::Zero(), Vec3(a - k.center_at(t_a_s)), Vec3(b - k.center_at(t_b_s)));
}

namespace {

// What an edge must satisfy: the static rule, and every keep-out at the times it is flown.
class EdgeCheck {
 public:
  EdgeCheck(const SegmentRule& rule, const RrtQuery& q) : rule_(rule), q_(q) {}
  bool operator()(const Vec3& a, double along_m, const Vec3& b) const {
    if (!rule_(a, b)) return false;
    if (q_.keep_outs.empty()) return true;
    const double t_a = q_.start_time_s + along_m / q_.speed_mps;
    const double t_b = t_a + (b - a).norm() / q_.speed_mps;
    for (const MovingKeepOut& k : q_.keep_outs)
      if (keep_out_distance(k, a, t_a, b, t_b) < k.radius_m) return false;
    return true;
  }

 private:
  const SegmentRule& rule_;
  const RrtQuery& q_;
};

// The growth direction held to the limits: pitch within the climb limit and, when it turns
// more than the turn limit from the incoming edge, rotated toward that edge (the largest
// rotation that keeps the limit, by bisection; the incoming direction itself always does).
std::optional<Vec3> limited(Vec3 dir, const std::optional<Vec3>& in, double max_turn, double max_climb, bool planar) {
  if (planar) dir.z() = 0.0;
  if ((planar || max_climb >= kPi / 2 - kUnlimitedAngleSlack_rad) && (!in || max_turn >= kPi)) {  // nothing to limit
    const double n = dir.norm();
    return n > 0.0 ? std::optional<Vec3>(dir / n) : std::nullopt;
  }
  const auto climb_limited = [&](Vec3 d) -> std::optional<Vec3> {
    if (planar) d.z() = 0.0;
    const double h = d.head<2>().norm();
    if (h <= 1e-12 * d.norm()) return std::nullopt;  // straight up or down
    const double pitch = std::clamp(std::atan2(d.z(), h), -max_climb, max_climb);
    return Vec3(std::cos(pitch) * d.x() / h, std::cos(pitch) * d.y() / h, std::sin(pitch));
  };
  auto out = climb_limited(dir);
  if (!in || max_turn >= kPi || (out && turn_rad(*in, *out) <= max_turn)) return out;
  const Vec3 a = in->normalized(), b = dir.normalized();
  const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
  // Rotation from a toward b by `f` of the angle between them (in their plane).
  Vec3 perp = b - a.dot(b) * a;
  if (perp.norm() < 1e-12) perp = std::abs(a.z()) < 0.9 ? a.cross(Vec3::UnitZ()) : a.cross(Vec3::UnitX());
  perp.normalize();
  const auto rotated = [&](double f) { return Vec3(std::cos(f * angle) * a + std::sin(f * angle) * perp); };
  std::optional<Vec3> best;
  double lo = 0.0, hi = std::min(1.0, max_turn / angle);
  for (int i = 0; i < 12; ++i) {
    const double f = i == 0 ? hi : 0.5 * (lo + hi);
    const auto d = climb_limited(rotated(f));
    if (d && turn_rad(*in, *d) <= max_turn) {
      best = d;
      if (i == 0) break;
      lo = f;
    } else {
      hi = f;
    }
  }
  return best;
}

bool path_ok(const std::vector<Vec3>& path, const EdgeCheck& ok, const PruneLimits& limits) {
  double along = 0.0;
  std::optional<Vec3> in = limits.max_turn_rad < kPi ? limits.start_direction : std::nullopt;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Vec3 seg = path[i] - path[i - 1];
    if (in && turn_rad(*in, seg) > limits.max_turn_rad + kAngleTolerance_rad) return false;
    if (!ok(path[i - 1], along, path[i])) return false;
    along += seg.norm();
    if (seg.norm() > 0.0 && limits.max_turn_rad < kPi) in = seg;
  }
  return !(in && limits.end_direction &&
           turn_rad(*in, *limits.end_direction) > limits.max_turn_rad + kAngleTolerance_rad);
}

// A search whose tree has not left its start after this many iterations is boxed in.
constexpr std::uint64_t kBoxedInIterations = 2000;

// The tree of one search and how it grows (P1 steps 2-6): goal-biased or sampled targets, steps
// within the turn and climb limits, edges checked by `ok`.
class RrtGrowth {
 public:
  RrtGrowth(const SegmentRule& rule, double max_turn, const RrtQuery& q, const RrtOptions& opt, const EdgeCheck& ok)
      : q_(q),
        opt_(opt),
        ok_(ok),
        max_turn_(max_turn),
        step_(opt.step_in(rule.world().bounds())),
        max_climb_(std::min(rule.max_climb_rad(), kPi / 2 - kUnlimitedAngleSlack_rad)),
        rng_(q.seed),
        chaos_(rng_.split(1).next_u64(), opt.arcsine_uniform),
        tree_(q.start, opt.max_nodes),
        // Step 2 of P1: the newest node within one step of the goal, and the last edge clear.
        // Under a turn limit a node one step away rarely faces the goal; within four steps the
        // tree can turn into it.
        arrive_m_(max_turn < kPi - kUnlimitedAngleSlack_rad ? 4.0 * step_ : step_),
        biased_(opt.lambda != 0.0 && q.bias_velocity_mps.squaredNorm() > 0.0) {
    goal_tried_.reserve(512);
    goal_tried_.push_back(0);
  }

  double step() const { return step_; }
  const RrtTree& tree() const { return tree_; }

  bool arrives(int i) const {
    const Vec3 last = q_.goal - tree_.pos(i);
    if (last.norm() > arrive_m_) return false;
    if (max_turn_ < kPi) {
      const auto in = incoming(i);
      if (in && turn_rad(*in, last) > max_turn_ + kAngleTolerance_rad) return false;
      // The way it comes into the goal (its own edge when the node is on the goal) against the way on.
      const std::optional<Vec3> into = last.norm() > 0.0 ? std::optional<Vec3>(last) : in;
      if (q_.goal_direction && into && turn_rad(*into, *q_.goal_direction) > max_turn_ + kAngleTolerance_rad)
        return false;
    }
    return ok_(tree_.pos(i), tree_.along(i), q_.goal);
  }

  // One iteration (steps 3-6): the node added, or -1 when the step is refused.
  int grow() {
    Vec3 target = q_.goal;
    int near = -1;
    bool to_goal = rng_.uniform01() < opt_.goal_bias;  // steps 3-4: goal bias
    if (to_goal) {
      // Each node grows toward the goal once: a node near the goal whose heading or climb cannot
      // reach it would otherwise take every goal-biased step.
      near = tree_.nearest_usable(q_.goal, [&](int i) { return !goal_tried_[static_cast<std::size_t>(i)]; });
      if (near < 0)
        to_goal = false;
      else
        goal_tried_[static_cast<std::size_t>(near)] = 1;
    }
    if (!to_goal) {  // step 5: a sample, chaotic or pseudo-random
      target = sample();
      near = tree_.nearest(target);
    }
    Vec3 dir = target - tree_.pos(near);
    const double dist = dir.norm();
    if (dist <= 1e-12) return -1;
    dir /= dist;
    if (!to_goal && biased_) dir += opt_.lambda * q_.bias_velocity_mps / q_.speed_mps;  // P1: + V_b
    const auto d = limited(dir, incoming(near), max_turn_, max_climb_, q_.planar);
    if (!d) return -1;
    // Short of the target only when heading straight at it: a step bent by the limits would
    // stop beside the target, needing a sharp turn to finish.
    const bool straight = (*d - dir.normalized()).norm() < kSamePoint_m;
    const double len = straight ? std::min(step_, dist) : step_;
    if (len < 1e-3 * step_) return -1;
    const Vec3 next = tree_.pos(near) + len * *d;
    if (!ok_(tree_.pos(near), tree_.along(near), next)) return -1;  // step 6
    const int added = tree_.add(next, near);
    goal_tried_.push_back(0);
    return added;
  }

 private:
  std::optional<Vec3> incoming(int i) const {
    const int p = tree_.parent(i);
    return p < 0 ? q_.start_direction : std::optional<Vec3>(tree_.pos(i) - tree_.pos(p));
  }
  Vec3 sample() {
    Vec3 target = opt_.chaotic ? chaos_.sample(q_.sample_box)
                               : Vec3(rng_.uniform(q_.sample_box.min.x(), q_.sample_box.max.x()),
                                      rng_.uniform(q_.sample_box.min.y(), q_.sample_box.max.y()),
                                      rng_.uniform(q_.sample_box.min.z(), q_.sample_box.max.z()));
    if (q_.planar) target.z() = q_.start.z();
    return target;
  }

  const RrtQuery& q_;
  const RrtOptions& opt_;
  const EdgeCheck& ok_;
  double max_turn_, step_, max_climb_;
  Rng rng_;
  ChaoticSampler chaos_;
  RrtTree tree_;
  double arrive_m_;
  bool biased_;
  std::vector<char> goal_tried_;
};

// The start and the goal in the free space; true with `res` complete when there is nothing to
// search (a failure, or the goal at the start).
bool settled_before_search(const SegmentRule& rule, const RrtQuery& q, RrtResult& res) {
  if (!rule.point_ok(q.start)) {
    res.fail(Reason::invalid, "start " + point_text(q.start) + " is outside the free space");
    return true;
  }
  if (!rule.point_ok(q.goal)) {
    res.fail(Reason::invalid, "goal " + point_text(q.goal) + " is outside the free space");
    return true;
  }
  if ((q.goal - q.start).norm() == 0.0) {
    res.succeed();
    res.path = res.raw = {q.start};
    return true;
  }
  return false;
}

// Step 8 and the shortcut; kept only when the whole route still holds at its new times (a
// shorter route reaches each point earlier, and keep-outs move).
void shorten(RrtResult& res, const RrtQuery& q, const RrtOptions& opt, double max_turn, const EdgeCheck& ok) {
  const bool timed = std::any_of(q.keep_outs.begin(), q.keep_outs.end(),
                                 [](const MovingKeepOut& k) { return k.velocity_mps.squaredNorm() > 0.0; });
  const PruneLimits limits{q.start_direction, q.goal_direction, max_turn, timed};
  if (opt.prune) {
    auto pruned = prune_within_step(res.path, q.uav_step_m, opt.lookahead, limits, ok);
    if (path_ok(pruned, ok, limits)) res.path = std::move(pruned);
  }
  if (opt.shortcut) {
    auto cut = shortcut_within_limits(res.path, limits, ok);
    if (path_ok(cut, ok, limits)) res.path = std::move(cut);
  }
}

}  // namespace

RrtResult rrt_search(const SegmentRule& rule, double max_turn, const RrtQuery& q, const RrtOptions& opt,
                     const StopCondition& stop) {
  RrtResult res;
  const EdgeCheck ok(rule, q);
  if (settled_before_search(rule, q, res)) return res;
  RrtGrowth growth(rule, max_turn, q, opt, ok);
  const std::uint64_t max_iterations = 50ull * static_cast<std::uint64_t>(opt.max_nodes);
  int reached = growth.arrives(0) ? 0 : -1;
  while (reached < 0) {
    const int nodes = growth.tree().size();
    if (stop.should_stop(res.iterations)) {
      res.fail(Reason::stopped, "stopped after " + std::to_string(nodes) + " nodes");
      break;
    }
    // A start every move from which is refused (boxed in by keep-outs) is given up early.
    if (nodes >= opt.max_nodes || res.iterations >= max_iterations ||
        (nodes == 1 && res.iterations >= kBoxedInIterations)) {
      res.fail(Reason::budget, "no route within " + std::to_string(nodes) + " nodes of " +
                                   std::to_string(growth.step()).substr(0, 5) +
                                   " m; raise planner.params.max_nodes (now " + std::to_string(opt.max_nodes) +
                                   ") or give a shorter step_m for narrow gaps");
      break;
    }
    ++res.iterations;
    const int added = growth.grow();
    if (added >= 0 && growth.arrives(added)) reached = added;
  }
  res.nodes = growth.tree().size();
  if (reached < 0) return res;
  res.raw = growth.tree().path_to(reached);  // step 7: backtrack
  if (res.raw.back() != q.goal) res.raw.push_back(q.goal);
  res.path = res.raw;
  res.succeed();
  shorten(res, q, opt, max_turn, ok);
  return res;
}

PlanResult RrtPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult out;
  const SegmentRule rule(world, pb.uav);
  std::vector<Vec3> stops{pb.uav.start};
  stops.insert(stops.end(), pb.via.begin(), pb.via.end());
  stops.push_back(pb.goal);
  RrtQuery q;
  q.sample_box = world.bounds();
  q.sample_box.max.z() = std::max(q.sample_box.min.z(), std::min(q.sample_box.max.z(), rule.ceiling_m()));
  q.planar = world.bounds().extent().z() <= 0.0;
  q.speed_mps = pb.uav.speed.cruise_mps;
  q.uav_step_m = pb.uav.speed.cruise_mps * 1.0;  // one second of flight
  if (pb.uav.heading_rad) q.start_direction = heading_vector(*pb.uav.heading_rad);
  out.route.waypoints = {pb.uav.start};
  for (std::size_t leg = 0; leg + 1 < stops.size(); ++leg) {
    q.start = stops[leg];
    q.goal = stops[leg + 1];
    q.seed = Rng(pb.seed).split(leg).next_u64();
    const RrtResult r = rrt_search(rule, pb.uav.max_turn_rad, q, options_, stop);
    out.stats.nodes_expanded += static_cast<std::uint64_t>(r.nodes);
    if (!r.solved()) {
      out.route.waypoints.clear();
      out.fail(r.reason, name_ + ": " + leg_name(leg, stops.size()) + " from " + point_text(q.start) + " to " +
                             point_text(q.goal) + ": " + r.message);
      return out;
    }
    for (std::size_t i = 1; i < r.path.size(); ++i) {
      const Vec3 seg = r.path[i] - out.route.waypoints.back();
      if (seg.norm() > 0.0) q.start_direction = seg;
      out.route.waypoints.push_back(r.path[i]);
    }
  }
  out.status = Status::solved;
  return out;
}

}  // namespace uavplan
