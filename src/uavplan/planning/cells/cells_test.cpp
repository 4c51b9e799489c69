#include <gtest/gtest.h>

#include "uavplan/planning/cells/cell_astar.h"
#include "uavplan/planning/cells/cellular_aco.h"
#include "uavplan/planning/registry.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {
namespace {

// 200 x 100 x 40 m, a 20 m block across the straight line from start to goal, ceiling 30 m.
World block_world() {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 100, 40)};
  ws.obstacles.push_back(Box{Vec3(90, 20, 0), Vec3(110, 80, 20)});
  ws.obstacles.push_back(Cylinder{Vec2(40, 80), 8, 0, 18});  // an "electromagnetic zone"
  return World(std::move(ws));
}

Problem block_problem() {
  Problem p;
  p.uav.id = "u";
  p.uav.start = Vec3(10, 50, 3);
  p.uav.radius_m = 1.0;
  p.uav.speed.cruise_mps = 2.0;
  p.uav.ceiling_m = 30.0;
  p.goal = Vec3(190, 50, 3);
  return p;
}

TEST(CellMap, HeightsToClear) {
  const World w = block_world();
  CellMapOptions o;
  o.cell_m = 5;
  o.inflation_m = 1.0;
  o.ceiling_m = 30;
  const CellMap m(w, o);
  EXPECT_EQ(m.nx(), 40);
  EXPECT_EQ(m.ny(), 20);
  EXPECT_DOUBLE_EQ(m.required_m(20, 10), 21.0);  // on the block: its top plus the radius
  EXPECT_DOUBLE_EQ(m.required_m(17, 10), 21.0);  // [85, 90] touches the block's inflated side
  EXPECT_DOUBLE_EQ(m.required_m(16, 10), 1.0);   // [80, 85] is 5 m away: free
  EXPECT_DOUBLE_EQ(m.required_m(8, 16), 19.0);   // the zone's equivalent height
  EXPECT_DOUBLE_EQ(m.required_m(0, 0), 1.0);
}

double highest(const std::vector<Vec3>& wp) {
  double z = 0;
  for (const auto& p : wp) z = std::max(z, p.z());
  return z;
}

void expect_clear(const PlanResult& r, const Problem& p, const World& w) {
  ASSERT_EQ(r.status, Status::solved) << r.message;
  const SegmentRule rule(w, p.uav);
  for (std::size_t i = 1; i < r.route.waypoints.size(); ++i) EXPECT_TRUE(rule(r.route.waypoints[i - 1], r.route.waypoints[i]));
}

// P2's claim: the altitude weight decides between going around and going over.
TEST(CellPlanners, AltitudeWeightChoosesAroundOrOver) {
  const World w = block_world();
  const Problem p = block_problem();
  for (const std::string name : {"cell_astar", "cellular_aco"}) {
    Params costly{{"cell_m", "5"}, {"w2", "1"}};    // altitude dear: around, low
    Params cheap{{"cell_m", "5"}, {"w2", "0"}};     // altitude free: over, short
    const auto around = make_planner(name, costly)->plan(p, w, {});
    const auto over = make_planner(name, cheap)->plan(p, w, {});
    expect_clear(around, p, w);
    expect_clear(over, p, w);
    EXPECT_LT(highest(around.route.waypoints), 20.0) << name;
    EXPECT_GT(highest(over.route.waypoints), 21.0) << name;
    EXPECT_LT(over.route.length_m(), around.route.length_m()) << name;
  }
}

TEST(CellularAco, NearTheOptimumAndIndependentOfThreads) {
  const World w = block_world();
  Problem p = block_problem();
  p.via = {Vec3(100, 90, 10)};
  CellularAcoOptions one;
  one.cells.cell_m = 5;
  one.threads = 1;
  CellularAcoOptions two = one;
  two.threads = 2;
  const auto a = CellularAcoPlanner(one).plan(p, w, {});
  const auto b = CellularAcoPlanner(two).plan(p, w, {});
  expect_clear(a, p, w);
  EXPECT_EQ(a.route.waypoints, b.route.waypoints);
  CellAStarOptions ao;
  ao.cells = one.cells;
  const auto opt = CellAStarPlanner(ao).plan(p, w, {});
  expect_clear(opt, p, w);
  const CellWorld cw(p, w, one.cells);
  const double ja = cell_route_cost(cw.graph, a.route.waypoints), jo = cell_route_cost(cw.graph, opt.route.waypoints);
  EXPECT_GE(ja, jo * (1 - 1e-9));  // A* is optimal for the same cost
  EXPECT_LT(ja, 1.10 * jo);
  // The route passes the via point.
  bool via = false;
  for (const auto& q : a.route.waypoints) via = via || (q - p.via[0]).norm() < 1e-9;
  EXPECT_TRUE(via);
}

}  // namespace
}  // namespace uavplan
