// The Planner interface: configured by an options struct, const while planning (one instance
// can serve many threads), expected failure is a status, misuse is an exception.
#pragma once

#include <string_view>

#include "uavplan/core/stop.h"
#include "uavplan/planning/problem.h"
#include "uavplan/world/world.h"

namespace uavplan {

class Planner {
 public:
  virtual ~Planner() = default;
  virtual std::string_view name() const = 0;

  // Validates (std::invalid_argument on a malformed problem), plans, and times the call.
  PlanResult plan(const Problem& problem, const World& world, const StopCondition& stop) const;

 private:
  virtual PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const = 0;
};

// Throws std::invalid_argument when the problem cannot be posed in this world: non-finite or
// out-of-bounds start, goal or via point, or one inside an obstacle, bad limits.
void validate_problem(const Problem& problem, const World& world);

}  // namespace uavplan
