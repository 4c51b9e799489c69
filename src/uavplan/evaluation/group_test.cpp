// P3's group through the mission planner, verified, and scored before and after smoothing.
#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/core/rng.h"

#include "uavplan/coordination/group/group_planner.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {
namespace {

Scenario p3_group(bool three_d) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-2, -2, 0), Vec3(20, 20, three_d ? 8 : 0)};
  const double obs[11][2] = {{4, 3},   {4, 4},   {4, 5}, {5, 3.5}, {5, 4.5}, {5, 5.5},
                             {5.5, 4}, {5.5, 5}, {6, 4}, {6, 5},   {6, 6}};
  for (const auto& o : obs) {
    if (three_d)
      ws.obstacles.push_back(Cylinder{Vec2(o[0], o[1]), 0.15, 0, 8});
    else
      ws.obstacles.push_back(Sphere{Vec3(o[0], o[1], 0), 0.15});
  }
  Scenario sc;
  sc.name = "p3";
  sc.world = World(std::move(ws));
  for (int k = 0; k < 9; ++k) {
    UavSpec u;
    u.id = "u" + std::to_string(k + 1);
    u.start = Vec3(k % 3, k / 3, three_d ? 1 : 0);
    u.goal = Vec3(15 + k % 3, 15 + k / 3, three_d ? 5 : 0);
    u.radius_m = 0.1;
    u.speed = {0, 1, 1};
    sc.uavs.push_back(u);
  }
  sc.mission.type = "group";
  sc.mission.separation_m = 0.5;
  sc.planner.algorithm = "apf";
  return sc;
}

class Group : public ::testing::TestWithParam<bool> {};

TEST_P(Group, PaperScenarioReachesVerifiesAndSmoothingLowersTheScore) {
  const Scenario sc = p3_group(GetParam());
  Plan plan = plan_mission(sc, {});
  const auto violations = finalize_plan(sc, plan);
  for (const auto& v : violations) ADD_FAILURE() << describe(v);
  EXPECT_EQ(plan.status, Status::solved) << plan.message;
  EXPECT_GE(plan.metrics.at("min_separation_m"), 0.5);

  const GroupResult g = plan_group(sc, ApfOptions::from_params({}, ApfField::improved), {});
  double before = 0, after = 0;
  for (const auto& u : g.uavs) {
    before += p3_score(u.raw, sc.world).sc;
    after += p3_score(u.smoothed, sc.world).sc;
  }
  EXPECT_LT(after, before);
}

INSTANTIATE_TEST_SUITE_P(FlatAnd3d, Group, ::testing::Bool());

TEST(Group, TraditionalBaselineAlsoPlansButWithoutSmoothing) {
  Scenario sc = p3_group(false);
  sc.planner.algorithm = "apf_traditional";
  const GroupResult g = plan_group(sc, ApfOptions::from_params({}, ApfField::traditional), {});
  for (const auto& u : g.uavs) EXPECT_EQ(u.raw, u.smoothed);
}

// n UAVs block to block (spacing 1.5 m) through random spheres that also stand among the goals:
// the goals in the middle of the block are walled in by UAVs that arrived first unless the
// late ones thread the gaps, and the field's local minima need the escape routes.
Scenario crowded(int n, std::uint64_t seed) {
  const int side_n = static_cast<int>(std::ceil(std::sqrt(n)));
  const double spacing = 1.5, side = spacing * side_n, span = 3 * side + 10;
  Scenario sc;
  sc.name = "crowded";
  for (int i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = Vec3(spacing * (i % side_n), spacing * (i / side_n), 0);
    u.goal = u.start + Vec3(span - side, span - side, 0);
    u.radius_m = 0.1;
    u.speed = {0, 1, 1};
    sc.uavs.push_back(u);
  }
  Rng rng(seed);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-2, -2, 0), Vec3(span + side + 2, span + side + 2, 0)};
  while (ws.obstacles.size() < static_cast<std::size_t>(side * side)) {
    const Vec3 c(rng.uniform(side + 2, span), rng.uniform(side + 2, span), 0);
    const double r = rng.uniform(0.1, 0.4);
    bool clear = true;
    for (const UavSpec& u : sc.uavs) clear &= (*u.goal - c).norm() >= r + 0.6;
    if (clear) ws.obstacles.push_back(Sphere{c, r});
  }
  sc.world = World(std::move(ws));
  sc.mission.type = "group";
  sc.mission.separation_m = 0.5;
  sc.planner.algorithm = "apf";
  return sc;
}

TEST(Group, CrowdedBlockThroughAFieldAllArriveSeparated) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Scenario sc = crowded(25, seed);
    Plan plan = plan_mission(sc, {});
    const auto violations = finalize_plan(sc, plan);
    for (const auto& v : violations) ADD_FAILURE() << "seed " << seed << ": " << describe(v);
    EXPECT_EQ(plan.status, Status::solved) << "seed " << seed << ": " << plan.message;
    EXPECT_GE(plan.metrics.at("min_separation_m"), 0.5);
  }
}

TEST(Group, SmoothedPointsStayNearTheirFrames) {
  const Scenario sc = crowded(25, 4);
  const GroupResult g = plan_group(sc, ApfOptions::from_params({}, ApfField::improved), {});
  int moved = 0;
  for (const auto& u : g.uavs) {
    ASSERT_EQ(u.raw.size(), u.smoothed.size());
    for (std::size_t k = 0; k < u.raw.size(); ++k) {
      EXPECT_LE((u.raw[k] - u.smoothed[k]).norm(), kDrift_steps * g.step_m + 1e-12);
      moved += u.raw[k] != u.smoothed[k];
    }
  }
  EXPECT_GT(moved, 100);
}

TEST(Group, UnreachableGoalsFailWithTheReasonAndTheOthersFly) {
  Scenario sc = p3_group(false);
  WorldSpec ws = sc.world.spec();
  ws.obstacles.push_back(Sphere{*sc.uavs[8].goal + Vec3(0.2, 0, 0), 0.15});  // u9's goal within its radius of it
  sc.world = World(std::move(ws));
  Plan plan = plan_mission(sc, {});
  const auto violations = finalize_plan(sc, plan);
  for (const auto& v : violations)
    if (v.kind != ViolationKind::not_planned) ADD_FAILURE() << describe(v);
  EXPECT_EQ(violations.size(), 1u);  // u9 has no trajectory
  for (const auto& u : plan.uavs) {
    if (u.id == "u9") {
      EXPECT_EQ(u.status, Status::failed);
      EXPECT_NE(u.message.find("goal is closer to an obstacle"), std::string::npos) << u.message;
    } else {
      EXPECT_EQ(u.status, Status::solved) << u.id << ": " << u.message;
    }
  }
}

}  // namespace
}  // namespace uavplan
