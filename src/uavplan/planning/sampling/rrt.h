// P1's RRT (sec. 2.3) and its baseline, one engine with options:
//  - common RRT: goal bias p_s, fixed step, arrive within a step; uniform pseudo-random samples;
//  - improved RRT: chaotic (logistic-map) samples, growth along (q_rand - q_near) biased by the
//    threatening obstacle's velocity, then P1's redundant-waypoint removal (5-look-ahead within
//    one UAV step) and a line-of-sight shortcut.
// Nodes live in flat arrays, nearest neighbours come from a nanoflann k-d tree. Edges hold the
// static world (SegmentRule: bounds, ceiling, climb, obstacles after inflation), the turn limit
// against the parent edge, and keep-outs that move at constant velocity (the local layer's
// inflated moving obstacles), checked exactly at the times the UAV would fly the edge.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "uavplan/core/status.h"
#include "uavplan/core/stop.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

// P1's improved RRT, or the common one it beats.
enum class RrtVariant { common, improved };

struct RrtOptions {
  double step_m = 0.0;           // epsilon; 0 = P1's 2 m, or diagonal / 50 for worlds larger than 100 m
  double goal_bias = 0.5;        // p_s: probability of growing toward the goal
  int max_nodes = 5000;          // per search (papers.md P1: 5000 per replan)
  bool chaotic = false;          // logistic-map samples (improved)
  bool arcsine_uniform = false;  // chaos transformed to uniform
  double lambda = 0.0;           // growth bias: dir = unit(q_rand - q_near) + lambda * V_b / cruise (improved: 1)
  bool prune = false;            // P1's 5-look-ahead redundant-waypoint removal (improved)
  int lookahead = 5;
  bool shortcut = false;  // line-of-sight shortcut after pruning (improved)

  static RrtOptions common();
  static RrtOptions improved();
  // planner.params: step_m, goal_bias, max_nodes, and for the improved one chaotic,
  // arcsine_uniform, lambda, prune, lookahead, shortcut.
  static RrtOptions from_params(const Params& params, RrtVariant variant);
  // The declaration of its parameters: reads them from r (params.h).
  static RrtOptions read(ParamReader& r, RrtVariant variant);
  // The step used in a world: step_m, or the default from the world's scale.
  double step_in(const Aabb& bounds) const;
};

// A sphere (a disc in a flat world) whose centre is `center` at time t0_s and moves with
// `velocity_mps`; a route must stay `radius_m` from its centre.
struct MovingKeepOut {
  Vec3 center = Vec3::Zero();
  Vec3 velocity_mps = Vec3::Zero();
  double radius_m = 0.0;
  double t0_s = 0.0;

  Vec3 center_at(double t_s) const { return center + (t_s - t0_s) * velocity_mps; }
};

// Smallest distance from the UAV flying a -> b over [t_a, t_b] to the keep-out's centre (exact:
// the relative motion is linear).
double keep_out_distance(const MovingKeepOut& k, const Vec3& a, double t_a_s, const Vec3& b, double t_b_s);

struct RrtQuery {
  Vec3 start = Vec3::Zero();
  Vec3 goal = Vec3::Zero();
  std::optional<Vec3> start_direction;  // the turn limit holds the first segment against it
  std::optional<Vec3> goal_direction;   // and the last against the way the route goes on
  Aabb sample_box;                      // where samples are drawn (within the world's bounds)
  bool planar = false;                  // grow in the start's horizontal plane only
  double start_time_s = 0.0;            // the UAV leaves the start then, at `speed_mps`
  double speed_mps = 1.0;
  std::span<const MovingKeepOut> keep_outs;
  Vec3 bias_velocity_mps = Vec3::Zero();  // V_b of the threatening obstacle (improved growth)
  double uav_step_m = 5.0;                // the UAV's distance per control step (pruning)
  std::uint64_t seed = 1;
};

// solved, or failed for invalid (an end outside the free space), budget (max_nodes or the
// iterations) or stopped.
struct RrtResult : Outcome {
  std::vector<Vec3> path;  // start ... goal
  std::vector<Vec3> raw;   // the tree's path before pruning and shortcutting
  int nodes = 0;
  std::uint64_t iterations = 0;
};

// Throws std::invalid_argument when the start breaks the rule (outside, inside an obstacle).
RrtResult rrt_search(const SegmentRule& rule, double max_turn_rad, const RrtQuery& query, const RrtOptions& options,
                     const StopCondition& stop);

// Planners `rrt` and `improved_rrt` on a static world: one search per leg (start, via points,
// goal), the next leg held to the turn limit against the last segment of the one before.
class RrtPlanner final : public Planner {
 public:
  RrtPlanner(std::string name, RrtOptions options) : name_(std::move(name)), options_(options) {}
  std::string_view name() const override { return name_; }
  const RrtOptions& options() const { return options_; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  std::string name_;
  RrtOptions options_;
};

}  // namespace uavplan
