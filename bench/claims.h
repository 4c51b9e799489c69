// What a plan claims, checked: the benchmark tables' solved and bad-claim counts.
#pragma once

#include <algorithm>
#include <vector>

#include "uavplan/evaluation/verifier.h"

namespace uavplan::bench {

struct Claims {
  int uavs = 0, solved = 0, bad = 0;  // bad: solved UAVs the verifier names
  void add(const Plan& plan, const std::vector<Violation>& violations) {
    for (const UavPlan& u : plan.uavs) {
      ++uavs;
      if (u.status != Status::solved) continue;
      ++solved;
      bad += std::any_of(violations.begin(), violations.end(), [&](const Violation& v) { return v.uav == u.id; });
    }
  }
  double solved_pct() const { return uavs ? 100.0 * solved / uavs : 0.0; }
};

}  // namespace uavplan::bench
