// P3's group through the mission planner, verified, and scored before and after smoothing.
#include <gtest/gtest.h>

#include "uavplan/coordination/group_planner.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {
namespace {

Scenario p3_group(bool three_d) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-2, -2, 0), Vec3(20, 20, three_d ? 8 : 0)};
  const double obs[11][2] = {{4, 3}, {4, 4}, {4, 5}, {5, 3.5}, {5, 4.5}, {5, 5.5}, {5.5, 4}, {5.5, 5}, {6, 4}, {6, 5}, {6, 6}};
  for (const auto& o : obs) {
    if (three_d) ws.obstacles.push_back(Cylinder{Vec2(o[0], o[1]), 0.15, 0, 8});
    else ws.obstacles.push_back(Sphere{Vec3(o[0], o[1], 0), 0.15});
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
  sc.mission.type = MissionType::group;
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

  const GroupResult g = plan_group(sc, ApfOptions::from_params({}, true), {});
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
  const GroupResult g = plan_group(sc, ApfOptions::from_params({}, false), {});
  for (const auto& u : g.uavs) EXPECT_EQ(u.raw, u.smoothed);
}

}  // namespace
}  // namespace uavplan
