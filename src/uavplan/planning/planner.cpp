#include "uavplan/planning/planner.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "uavplan/core/text.h"

namespace uavplan {
namespace {

void check_point(const std::string& what, const Vec3& p, const World& world) {
  if (!p.allFinite()) throw std::invalid_argument(what + " is not finite");
  if (!world.in_bounds(p)) throw std::invalid_argument(what + " " + point_text(p) + " is outside the world bounds");
  if (world.clearance(p, 1e-9) <= 0.0)
    throw std::invalid_argument(what + " " + point_text(p) + " is inside an obstacle");
}

}  // namespace

void validate_problem(const Problem& pb, const World& world) {
  const UavSpec& u = pb.uav;
  check_point("start", u.start, world);
  check_point("goal", pb.goal, world);
  for (std::size_t i = 0; i < pb.via.size(); ++i) check_point("via point " + std::to_string(i), pb.via[i], world);
  if (!(u.radius_m >= 0.0) || !std::isfinite(u.radius_m)) throw std::invalid_argument("radius must be >= 0");
  if (!(u.speed.cruise_mps > 0.0) || !std::isfinite(u.speed.cruise_mps))
    throw std::invalid_argument("cruise speed must be positive");
  if (!(u.max_turn_rad > 0.0) || !(u.max_climb_rad > 0.0))
    throw std::invalid_argument("turn and climb limits must be positive");
}

PlanResult Planner::plan(const Problem& problem, const World& world, const StopCondition& stop) const {
  validate_problem(problem, world);
  const auto t0 = std::chrono::steady_clock::now();
  PlanResult r;
  try {
    r = do_plan(problem, world, stop);
  } catch (const Stopped&) {
    r = PlanResult{};
    r.reason = Reason::stopped;
    r.message = "stopped (time limit or interrupt) while setting up";
  }
  // A failure a planner did not classify: the stop came first, or it found no route it could fly.
  if (r.status != Status::solved && r.reason == Reason::none)
    r.reason = stop.should_stop() ? Reason::stopped : Reason::no_route;
  r.stats.plan_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace uavplan
