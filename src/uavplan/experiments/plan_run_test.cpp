#include "uavplan/experiments/plan_run.h"

#include <gtest/gtest.h>

#include <set>

#include "uavplan/experiments/journal.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan {
namespace {

const std::string kDemoScenario = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/demo.yaml";

TEST(PlanAndVerify, PlansVerifiesAndKeepsTheRequestsLimits) {
  const Scenario sc = load_scenario(kDemoScenario);
  const VerifiedPlan v = plan_and_verify(sc, {});
  EXPECT_EQ(v.plan.status, Status::solved) << v.plan.message;
  EXPECT_TRUE(v.violations.empty());
  EXPECT_EQ(v.plan.seed, sc.seed.value_or(1));
  PlanRequest other;
  other.seed = 7;
  other.algorithm = "rrt";
  const VerifiedPlan r = plan_and_verify(sc, other);
  EXPECT_EQ(r.plan.seed, 7u);
  EXPECT_EQ(r.plan.algorithm, "rrt");
  // The memory cap is the request's: too small for astar's grid, a bad request.
  PlanRequest tiny;
  tiny.max_memory_bytes = 1024;
  EXPECT_THROW(plan_and_verify(sc, tiny), std::invalid_argument);
  // A planner the mission does not plan with is refused by name.
  PlanRequest wrong;
  wrong.algorithm = "apf";
  EXPECT_NO_THROW(plan_and_verify(sc, wrong));  // an independent mission takes any planner
  PlanRequest unknown;
  unknown.algorithm = "nosuch";
  EXPECT_THROW(plan_and_verify(sc, unknown), std::invalid_argument);
}

TEST(PlanAndVerify, DefaultCapsAreShares) {
  if (default_memory_cap_bytes() == 0) GTEST_SKIP() << "the machine does not say its memory";
  EXPECT_EQ(default_run_memory_cap_bytes(4), default_memory_cap_bytes() / 4);
  EXPECT_LE(default_run_memory_cap_bytes(0), default_memory_cap_bytes());
}

TEST(PendingRuns, RanksShareTheRunsNotDoneEachOnce) {
  std::vector<RunSpec> runs(10);
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i].index = i;
  std::vector<RunRecord> previous(2);
  previous[0].spec.index = 2;
  previous[1].spec.index = 5;
  std::multiset<std::size_t> all;
  for (int rank = 0; rank < 3; ++rank)
    for (const RunSpec& r : pending_runs(runs, previous, rank, 3)) all.insert(r.index);
  EXPECT_EQ(all, (std::multiset<std::size_t>{0, 1, 3, 4, 6, 7, 8, 9}));
  EXPECT_EQ(pending_runs(runs, {}, 0, 1).size(), 10u);
}

}  // namespace
}  // namespace uavplan
