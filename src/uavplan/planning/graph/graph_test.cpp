#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/core/rng.h"
#include "uavplan/planning/graph/aco_voronoi.h"
#include "uavplan/planning/registry.h"
#include "uavplan/world/threat.h"

namespace uavplan {
namespace {

World threat_world(std::vector<Radar> radars, std::vector<Obstacle> obstacles = {}) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(600, 600, 100)};
  ws.radars = std::move(radars);
  ws.obstacles = std::move(obstacles);
  return World(std::move(ws));
}

UavSpec uav() {
  UavSpec u;
  u.id = "u";
  u.start = Vec3(20, 20, 50);
  u.radius_m = 0.5;
  return u;
}

// Four threats on a square: the Voronoi diagram is the two lines between them, crossing at the
// square's centre; each edge lies midway between its two threats.
TEST(ThreatRoadmap, EdgesRunMidwayBetweenNeighbouringThreats) {
  const World w = threat_world({{Vec3(200, 200, 50), 1}, {Vec3(400, 200, 50), 1}, {Vec3(400, 400, 50), 1}, {Vec3(200, 400, 50), 1}});
  const SegmentRule rule(w, uav());
  const Roadmap map = threat_roadmap(w, rule, 50.0, {});
  EXPECT_EQ(map.sites, 4u);
  EXPECT_FALSE(map.from_obstacles);
  ASSERT_EQ(map.edges.size(), 4u);  // four rays from the centre to the bounds
  for (const Roadmap::Edge& e : map.edges) {
    const Vec3 a = map.vertices[e.a], b = map.vertices[e.b];
    EXPECT_NEAR(std::min((a - Vec3(300, 300, 50)).norm(), (b - Vec3(300, 300, 50)).norm()), 0.0, 1e-6);
    EXPECT_NEAR(e.length_m, 300.0, 1e-6);  // to the bounds
    EXPECT_NEAR(e.cost, p1_edge_cost(a, b, w, {}), 1e-9);
    EXPECT_NEAR(e.cost, 0.5 * p1_threat_cost(a, b, w.radars()) + 0.5 * 300.0, 1e-9);  // P1 eq. 3, k1 = 0.5
  }
}

TEST(ThreatRoadmap, EdgesThroughObstaclesAreDropped) {
  const std::vector<Radar> r{{Vec3(200, 200, 50), 1}, {Vec3(400, 200, 50), 1}, {Vec3(400, 400, 50), 1}, {Vec3(200, 400, 50), 1}};
  const World w = threat_world(r, {Cylinder{Vec2(300, 500), 20, 0, 100}});  // on the northern ray
  const Roadmap map = threat_roadmap(w, SegmentRule(w, uav()), 50.0, {});
  EXPECT_EQ(map.edges.size(), 3u);
}

// The colony against the optimum on random threat fields: within 5 % of Dijkstra's cost.
TEST(AcoVoronoi, ColonyWithinFivePercentOfTheOptimum) {
  for (int trial = 0; trial < 6; ++trial) {
    Rng rng(100 + trial);
    std::vector<Radar> radars;
    const int n = 10 + 38 * trial;
    for (int k = 0; k < n; ++k) radars.push_back({Vec3(rng.uniform(30, 570), rng.uniform(30, 570), 50), 1e6});
    const World w = threat_world(radars);
    Problem p;
    p.uav = uav();
    p.uav.start = Vec3(5, 5, 50);
    p.goal = Vec3(595, 595, 50);
    const PlanResult opt = make_planner("voronoi_dijkstra", {})->plan(p, w, {});
    const PlanResult aco = make_planner("aco_voronoi", {})->plan(p, w, {});
    ASSERT_EQ(opt.status, Status::solved) << opt.message;
    ASSERT_EQ(aco.status, Status::solved) << aco.message;
    auto cost = [&](const PlanResult& r) {
      double c = 0.0;
      for (std::size_t i = 1; i < r.route.waypoints.size(); ++i) c += p1_edge_cost(r.route.waypoints[i - 1], r.route.waypoints[i], w, {});
      return c;
    };
    EXPECT_LE(cost(aco), 1.05 * cost(opt)) << n << " threats";
    EXPECT_GE(cost(aco), cost(opt) * (1.0 - 1e-9)) << n << " threats";
  }
}

TEST(AcoVoronoi, DepositRuleAndBadParameters) {
  EXPECT_NO_THROW(make_planner("aco_voronoi", {{"deposit", "cost"}}));
  EXPECT_THROW(make_planner("aco_voronoi", {{"deposit", "both"}}), std::invalid_argument);
  EXPECT_THROW(make_planner("voronoi_dijkstra", {{"ants", "5"}}), std::invalid_argument);
}

}  // namespace
}  // namespace uavplan
