// One contract every registered planner passes (OMPL-style): start = goal, a goal inside an
// obstacle, an unreachable goal, the stop condition, determinism, and valid routes.
#include <gtest/gtest.h>

#include <algorithm>

#include "uavplan/core/text.h"

#include "uavplan/planning/registry.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {
namespace {

// A 100 x 100 x 40 world with a wall that has a gap, and a closed cell around (85, 85, 20).
World contract_world() {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 100, 40)};
  ws.obstacles.push_back(Box{Vec3(45, 0, 0), Vec3(55, 70, 40)});  // wall, gap at y > 70
  const Vec3 c(85, 85, 20);
  const double in = 5, out = 7;
  ws.obstacles.push_back(Box{c + Vec3(-out, -out, -out), c + Vec3(out, out, -in)});  // floor
  ws.obstacles.push_back(Box{c + Vec3(-out, -out, in), c + Vec3(out, out, out)});    // roof
  ws.obstacles.push_back(Box{c + Vec3(-out, -out, -in), c + Vec3(-in, out, in)});
  ws.obstacles.push_back(Box{c + Vec3(in, -out, -in), c + Vec3(out, out, in)});
  ws.obstacles.push_back(Box{c + Vec3(-in, -out, -in), c + Vec3(in, -in, in)});
  ws.obstacles.push_back(Box{c + Vec3(-in, in, -in), c + Vec3(in, out, in)});
  return World(std::move(ws));
}

Problem problem(const Vec3& s, const Vec3& g) {
  Problem p;
  p.uav.id = "u";
  p.uav.start = s;
  p.uav.radius_m = 0.5;
  p.uav.max_turn_rad = deg_to_rad(60);
  p.uav.max_climb_rad = deg_to_rad(30);
  p.uav.heading_rad = 0.0;
  p.goal = g;
  return p;
}

void expect_valid_route(const PlanResult& r, const Problem& p, const World& w) {
  ASSERT_EQ(r.status, Status::solved) << r.message;
  const auto& pts = r.route.waypoints;
  ASSERT_FALSE(pts.empty());
  EXPECT_EQ(pts.front(), p.uav.start);
  EXPECT_EQ(pts.back(), p.goal);
  const SegmentRule rule(w, p.uav);
  for (std::size_t i = 1; i < pts.size(); ++i) EXPECT_TRUE(rule(pts[i - 1], pts[i])) << "segment " << i;
  EXPECT_TRUE(check_route_limits(pts, p.uav).empty());
}

class PlannerContract : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<Planner> planner = make_planner(GetParam(), {});
  World world = contract_world();
};

TEST_P(PlannerContract, StartEqualsGoal) {
  const Problem p = problem(Vec3(10, 10, 10), Vec3(10, 10, 10));
  expect_valid_route(planner->plan(p, world, {}), p, world);
}

bool complete(const std::string& name) {
  for (const auto& info : planner_catalog())
    if (info.name == name) return info.complete;
  return true;
}

bool relaxed(const std::string& name) {
  for (const auto& info : planner_catalog())
    if (info.name == name) return info.relaxed;
  return false;
}

TEST_P(PlannerContract, FindsTheGapAndKeepsTheLimits) {
  const Problem p = problem(Vec3(10, 10, 10), Vec3(90, 10, 10));
  const PlanResult r = planner->plan(p, world, {});
  if (!complete(GetParam()) && r.status != Status::solved) {
    EXPECT_FALSE(r.message.empty());  // a local method may fail, but says why
    return;
  }
  expect_valid_route(r, p, world);
  // Around the wall's end at y = 70: at least via its two corners, and (for a complete search)
  // not much more.
  EXPECT_GT(r.route.length_m(), 2 * std::hypot(35.0, 60.0) + 10.0);
  if (complete(GetParam())) {
    EXPECT_LT(r.route.length_m(), 1.1 * (2 * std::hypot(35.0, 61.0) + 10.0));
  }
}

TEST_P(PlannerContract, GoalInsideAnObstacleIsMisuse) {
  EXPECT_THROW(planner->plan(problem(Vec3(10, 10, 10), Vec3(50, 10, 10)), world, {}), std::invalid_argument);
  EXPECT_THROW(planner->plan(problem(Vec3(10, 10, 10), Vec3(150, 10, 10)), world, {}), std::invalid_argument);
}

TEST_P(PlannerContract, UnreachableGoalFailsWithAReason) {
  const PlanResult r = planner->plan(problem(Vec3(10, 10, 10), Vec3(85, 85, 20)), world, {});
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(r.route.waypoints.empty());
  EXPECT_NE(r.reason, Reason::none) << r.message;  // why, as a value
  EXPECT_NE(r.reason, Reason::stopped) << r.message;
}

TEST_P(PlannerContract, HonoursACancelledStop) {
  std::atomic<bool> cancel{true};
  const PlanResult r =
      planner->plan(problem(Vec3(10, 10, 10), Vec3(90, 10, 10)), world, StopCondition::cancel_flag(&cancel));
  EXPECT_NE(r.status, Status::solved);
  EXPECT_EQ(r.reason, Reason::stopped) << r.message;  // the batch's `timeout` reads this
}

TEST_P(PlannerContract, SameInputSameRoute) {
  const Problem p = problem(Vec3(10, 80, 10), Vec3(90, 85, 30));  // over the wall's end
  const PlanResult a = planner->plan(p, world, {}), b = planner->plan(p, world, {});
  if (relaxed(GetParam()) && a.status != Status::solved) {  // fails the same way, saying why
    EXPECT_FALSE(a.message.empty());
    EXPECT_EQ(a.message, b.message);
    return;
  }
  ASSERT_EQ(a.status, Status::solved) << a.message;
  expect_valid_route(a, p, world);
  EXPECT_EQ(a.route.waypoints, b.route.waypoints);
}

std::vector<std::string> names() {
  std::vector<std::string> n;
  for (const auto& p : planner_catalog()) n.push_back(p.name);
  return n;
}

INSTANTIATE_TEST_SUITE_P(Registered, PlannerContract, ::testing::ValuesIn(names()),
                         [](const auto& param_info) { return param_info.param; });

TEST(Registry, UnknownNamesAndParametersAreErrors) {
  EXPECT_THROW(make_planner("nope", {}), std::invalid_argument);
  EXPECT_THROW(make_planner("astar", {{"cel_m", "3"}}), std::invalid_argument);
  EXPECT_THROW(make_planner("astar", {{"cell_m", "abc"}}), std::invalid_argument);
  EXPECT_NO_THROW(make_planner("astar", {{"cell_m", "3"}}));
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

TEST(Registry, ListsEveryPlannersParametersWithTheirDefaults) {
  for (const PlannerInfo& info : planner_catalog()) {
    const std::vector<ParamDecl> params = planner_parameters(info.name);
    EXPECT_FALSE(params.empty()) << info.name;
    for (const ParamDecl& d : params) {
      EXPECT_TRUE(planner_accepts(info.name, d.key, d.default_value) || d.default_value == "nan" ||
                  d.default_value == "inf")
          << info.name << " " << d.key << "=" << d.default_value;
      EXPECT_FALSE(d.doc.empty()) << info.name << " " << d.key;  // each one says what it is
      // Its declared range is what it takes: the ends in, just past them out.
      if (d.kind == ParamKind::number || d.kind == ParamKind::integer) {
        EXPECT_TRUE(planner_accepts(info.name, d.key, num_text(d.lo))) << info.name << " " << d.key;
        EXPECT_FALSE(planner_accepts(info.name, d.key, num_text(d.hi * 2 + 1))) << info.name << " " << d.key;
      }
      for (const std::string& c : d.choices) EXPECT_TRUE(planner_accepts(info.name, d.key, c)) << d.key << " " << c;
    }
  }
  const auto rrt = planner_parameters("rrt");
  EXPECT_EQ(std::count_if(rrt.begin(), rrt.end(), [](const ParamDecl& d) { return d.key == "goal_bias"; }), 1);
  EXPECT_THROW(planner_parameters("nosuch"), std::invalid_argument);
  EXPECT_FALSE(planner_accepts("nosuch", "cell_m", "1"));
  EXPECT_FALSE(planner_accepts("astar", "cel_m", "1"));  // unknown key
  EXPECT_FALSE(planner_accepts("astar", "cell_m", "x"));
  EXPECT_FALSE(planner_accepts("aco_voronoi", "deposit", "both"));
  EXPECT_FALSE(planner_accepts("directional_astar", "step_cells", "0.3"));  // a rule beyond the range
  EXPECT_NE(planner_catalog_text(true).find("| `goal_bias` | number | [0, 1] | 0.5 |"), std::string::npos);
}

}  // namespace
}  // namespace uavplan
