#include "uavplan/planning/search/directional_astar.h"

#include <gtest/gtest.h>

#include <thread>

#include "uavplan/core/rng.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {
namespace {

Problem problem(const Vec3& s, const Vec3& g, std::optional<double> heading) {
  Problem p;
  p.uav.id = "u";
  p.uav.start = s;
  p.uav.radius_m = 1.0;
  p.uav.max_turn_rad = deg_to_rad(60);
  p.uav.max_climb_rad = deg_to_rad(30);
  p.uav.heading_rad = heading;
  p.goal = g;
  return p;
}

void expect_feasible(const PlanResult& r, const Problem& p, const World& w) {
  ASSERT_EQ(r.status, Status::solved) << r.message;
  const auto& pts = r.route.waypoints;
  EXPECT_EQ(pts.front(), p.uav.start);
  EXPECT_EQ(pts.back(), p.goal);
  EXPECT_TRUE(check_route_limits(pts, p.uav).empty());  // includes the first turn against the heading
  const SegmentRule rule(w, p.uav);
  for (std::size_t i = 1; i < pts.size(); ++i) EXPECT_TRUE(rule(pts[i - 1], pts[i]));
}

// A 30 x 30 x 10 km world with six random spheres in its middle.
World random_sphere_world(Rng& r) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(30000, 30000, 10000)};
  for (int k = 0; k < 6; ++k)
    ws.obstacles.push_back(
        Sphere{Vec3(r.uniform(8000, 22000), r.uniform(8000, 22000), r.uniform(0, 10000)), r.uniform(1500, 4000)});
  return World(std::move(ws));
}

TEST(DirectionalAStar, RandomSphereWorldsKeepTurnAndClimbLimits) {
  Rng r(51);
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  int solved = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const World w = random_sphere_world(r);
    const Problem p = problem(Vec3(5000, 5000, 2000), Vec3(28000, 27000, 6000), r.uniform(-kPi, kPi));
    if (w.point_collides(p.uav.start, 10) || w.point_collides(p.goal, 10)) continue;
    const PlanResult res = planner.plan(p, w, {});
    // A start facing the nearby boundary may have no room to turn: then a clear failure.
    if (res.status != Status::solved) {
      EXPECT_FALSE(res.message.empty());
      continue;
    }
    expect_feasible(res, p, w);
    ++solved;
  }
  EXPECT_GT(solved, 6);
}

// Through via points (a route mission, a sortie from home): one search per leg, each leaving with
// the heading the last arrived with, so the route passes every via point exactly and keeps the
// turn limit at them too, the way back from a via point behind the UAV included.
TEST(DirectionalAStar, ViaPointsArePassedInOrderWithinTheTurnLimit) {
  Rng r(61);
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  int solved = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const World w = random_sphere_world(r);
    Problem p = problem(Vec3(5000, 5000, 2000), Vec3(26000, 6000, 3000), r.uniform(-kPi, kPi));
    p.via = {Vec3(r.uniform(8000, 24000), r.uniform(18000, 27000), r.uniform(2000, 8000)), Vec3(6000, 24000, 5000)};
    bool clear = !w.point_collides(p.uav.start, 10) && !w.point_collides(p.goal, 10);
    for (const Vec3& v : p.via) clear = clear && !w.point_collides(v, 10);
    if (!clear) continue;
    const PlanResult res = planner.plan(p, w, {});
    if (res.status != Status::solved) {
      EXPECT_FALSE(res.message.empty());
      continue;
    }
    expect_feasible(res, p, w);
    const auto& pts = res.route.waypoints;
    auto at = pts.begin();
    for (const Vec3& v : p.via) {
      at = std::find(at, pts.end(), v);
      ASSERT_NE(at, pts.end()) << "trial " << trial << ": via point not passed in order";
    }
    ++solved;
  }
  EXPECT_GT(solved, 4);
}

// A concave trap in front of the start: the greedy direction leads into a dead zone; the
// search must close it and go around.
TEST(DirectionalAStar, EscapesAConcaveDeadZone) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(60, 40, 0)};
  ws.obstacles.push_back(Box{Vec3(30, 10, -1), Vec3(32, 30, 1)});  // the back wall
  ws.obstacles.push_back(Box{Vec3(18, 10, -1), Vec3(32, 12, 1)});  // lower arm
  ws.obstacles.push_back(Box{Vec3(18, 28, -1), Vec3(32, 30, 1)});  // upper arm
  const World w(std::move(ws));
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1"}}));
  const Problem p = problem(Vec3(5, 20, 0), Vec3(55, 20, 0), 0.0);
  const PlanResult res = planner.plan(p, w, {});
  expect_feasible(res, p, w);
  EXPECT_GT(res.route.length_m(), 50.0 + 2.0);
}

TEST(DirectionalAStar, NearestEquivalentStaysInsideTheCone) {
  // Straight ahead is blocked close by: with a 20 degree limit the route may not swerve sharply.
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 100, 0)};
  ws.obstacles.push_back(Sphere{Vec3(50, 50, 0), 10});
  const World w(std::move(ws));
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1"}, {"directions", "5"}}));
  Problem p = problem(Vec3(10, 50, 0), Vec3(90, 50, 0), 0.0);
  p.uav.max_turn_rad = deg_to_rad(20);
  expect_feasible(planner.plan(p, w, {}), p, w);
}

// P4's world shape with 1 km cells: a short step cannot climb at 30 deg (a level takes sqrt(3)
// cells across), so a search that must climb 20 levels ends after the start's neighbourhood
// instead of exhausting its level; a long enough step climbs. The length bound stops a search
// whose routes cannot be short enough, and leaves one alone that can.
TEST(DirectionalAStar, ShortStepsThatCannotClimbAndTheLengthBoundEndEarly) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(65000, 65000, 30000)};
  ws.obstacles.push_back(Cylinder{Vec2(20000, 15000), 4000, 0, 30000});
  const World w(std::move(ws));
  const Problem p = problem(Vec3(3000, 4000, 5000), Vec3(37000, 28000, 25000), deg_to_rad(90));
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  DirectionalQuery q = planner.query_for(p, w);
  q.heading_states = false;
  q.incumbent_weight = 1.0;  // the exact search's own length bound
  DirectionalSearch search;
  q.step_cells = 1.2;
  const DirectionalRoute flat = search.run(w, q, {});
  EXPECT_FALSE(flat.solved());
  EXPECT_LT(flat.expanded, 200u);  // the level holds 66 x 66 points
  q.step_cells = 2.5;
  const DirectionalRoute climbs = search.run(w, q, {});
  ASSERT_TRUE(climbs.solved());
  EXPECT_GT(climbs.length_m, (p.goal - p.uav.start).norm());
  q.max_length_m = climbs.length_m + 1.0;
  const DirectionalRoute bounded = search.run(w, q, {});
  ASSERT_TRUE(bounded.solved());
  EXPECT_DOUBLE_EQ(bounded.length_m, climbs.length_m);
  q.max_length_m = climbs.length_m - 1.0;
  const DirectionalRoute cut = search.run(w, q, {});
  EXPECT_FALSE(cut.solved());
  EXPECT_LT(cut.expanded, climbs.expanded);
}

// Engines sharing one set of cone tables, searching side by side with different steps and
// direction counts, find what engines of their own find.
TEST(DirectionalAStar, SharedConeTablesGiveTheSameRoutesAcrossThreads) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(40000, 40000, 20000)};
  ws.obstacles.push_back(Sphere{Vec3(18000, 17000, 9000), 5000});
  ws.obstacles.push_back(Sphere{Vec3(27000, 30000, 12000), 4000});
  const World w(std::move(ws));
  const Problem p = problem(Vec3(3000, 4000, 6000), Vec3(36000, 35000, 14000), deg_to_rad(90));
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  std::vector<DirectionalQuery> qs;
  for (const double step : {1.8, 2.4, 3.0})
    for (const int m : {3, 5}) {
      DirectionalQuery q = planner.query_for(p, w);
      q.step_cells = step;
      q.directions = m;
      qs.push_back(q);
    }
  std::vector<DirectionalRoute> alone;
  for (const auto& q : qs) alone.push_back(DirectionalSearch().run(w, q, {}));
  const auto cones = std::make_shared<DirectionalCones>();
  std::vector<DirectionalRoute> shared(qs.size());
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t)
    threads.emplace_back([&, t] {
      DirectionalSearch engine(cones);
      for (std::size_t i = 0; i < qs.size(); ++i) {
        const std::size_t k = (i + 2 * t) % qs.size();  // each thread its own order
        const DirectionalRoute r = engine.run(w, qs[k], {});
        if (t == 0)
          shared[k] = r;
        else
          EXPECT_EQ(r.waypoints, alone[k].waypoints) << k;
      }
    });
  for (auto& th : threads) th.join();
  for (std::size_t k = 0; k < qs.size(); ++k) {
    ASSERT_TRUE(alone[k].solved()) << k;
    EXPECT_EQ(shared[k].waypoints, alone[k].waypoints) << k;
    EXPECT_EQ(shared[k].expanded, alone[k].expanded) << k;
  }
}

// Climbing 8 km at 20 deg in a 12 km square: the route spirals up. With the climb bound the
// search expands far fewer nodes than with P4's Euclidean h, and its route keeps every limit and
// the length.
TEST(DirectionalAStar, ClimbBoundSparesASpiralSearch) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(12000, 12000, 12000)};
  const World w(std::move(ws));
  Problem p = problem(Vec3(2000, 2000, 1000), Vec3(10000, 10000, 9000), 0.0);
  p.uav.max_climb_rad = deg_to_rad(20);
  const DirectionalAStarPlanner euclid(
      DirectionalAStarOptions::from_params({{"cell_m", "500"}, {"climb_bound", "false"}}));
  const DirectionalAStarPlanner climb(DirectionalAStarOptions::from_params({{"cell_m", "500"}}));
  const PlanResult a = euclid.plan(p, w, {});
  const PlanResult b = climb.plan(p, w, {});
  expect_feasible(a, p, w);
  expect_feasible(b, p, w);
  EXPECT_GE(b.route.length_m(), 8000.0 / std::sin(deg_to_rad(20)) - 1e-6);  // the bound holds
  EXPECT_NEAR(b.route.length_m(), a.route.length_m(), 1e-6);                // both optimal on the same lattice
  EXPECT_LT(2 * b.stats.nodes_expanded, a.stats.nodes_expanded);
}

// The relaxed heuristic (the exact length left without turn limits, from a reverse search) is a
// consistent lower bound: on random sphere worlds every route keeps its length, and the search
// expands a fraction of the states that the Euclidean and climb bound expand.
TEST(DirectionalAStar, RelaxedHeuristicKeepsTheLengthsAndOpensFewer) {
  Rng r(77);
  const DirectionalAStarPlanner plain(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  const DirectionalAStarPlanner relaxed(
      DirectionalAStarOptions::from_params({{"cell_m", "1000"}, {"relaxed_heuristic", "true"}}));
  std::uint64_t plain_expanded = 0, relaxed_expanded = 0;
  int solved = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const World w = random_sphere_world(r);
    const Problem p = problem(Vec3(4000, 5000, 2000), Vec3(27000, 26000, 7000), r.uniform(-kPi, kPi));
    if (w.point_collides(p.uav.start, 10) || w.point_collides(p.goal, 10)) continue;
    const PlanResult a = plain.plan(p, w, {});
    const PlanResult b = relaxed.plan(p, w, {});
    ASSERT_EQ(a.status, b.status) << trial << ": " << a.message << " | " << b.message;
    if (a.status != Status::solved) continue;
    expect_feasible(b, p, w);
    EXPECT_NEAR(b.route.length_m(), a.route.length_m(), 1e-6) << trial;
    plain_expanded += a.stats.nodes_expanded;
    relaxed_expanded += b.stats.nodes_expanded;
    ++solved;
  }
  EXPECT_GT(solved, 5);
  EXPECT_LT(2 * relaxed_expanded, plain_expanded);  // 2.7x fewer when written
}

// The counts the bench sets beside P4's "OPEN grid cells": with P4's one state per lattice point
// every state opened but the start and the goal is a point of its own; with heading sectors a
// point holds up to eight states.
TEST(DirectionalAStar, CellsOpenedCountLatticePointsOnce) {
  Rng r(91);
  int solved = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const World w = random_sphere_world(r);
    const Vec3 start(4000, 5000, 2000), goal(27000, 26000, 7000);
    if (w.point_collides(start, 10) || w.point_collides(goal, 10)) continue;
    const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
    DirectionalQuery q = planner.query_for(problem(start, goal, 0.5), w);
    q.incumbent_weight = 1.0;  // one search: opened counts its states once each
    DirectionalSearch engine;
    for (const bool sectors : {false, true}) {
      q.heading_states = sectors;
      const DirectionalRoute a = engine.run(w, q, {});
      const DirectionalRoute b = engine.run(w, q, {});  // the same buffers again: the stamps start anew
      EXPECT_EQ(a.cells_opened, b.cells_opened);
      if (!a.solved()) continue;
      EXPECT_LE(a.opened, a.generated + 1);
      if (sectors) {
        EXPECT_LT(a.cells_opened, a.opened - 2);  // some point is passed in two sectors
        EXPECT_GE(8 * a.cells_opened, a.opened - 2);
      } else {
        EXPECT_EQ(a.cells_opened, a.opened - 2);  // less the start and the goal
        ++solved;
      }
    }
  }
  EXPECT_GT(solved, 1);
}

// The exact search bounded by a first route found with f = g + 1.2 h (the default): never a longer
// route than the exact search's alone, and fewer lattice points opened, since no node whose f is
// above the bound goes on the list. With the relaxed heuristic, the second search resumes the
// first's reverse search rather than starting it again.
TEST(DirectionalAStar, AFirstRoutesBoundKeepsTheLengthsAndOpensFewerCells) {
  Rng r(83);
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  ASSERT_EQ(planner.options().incumbent_weight, 1.2);
  std::uint64_t cells_alone = 0, cells_bounded = 0, reverse_alone = 0, reverse_bounded = 0;
  int solved = 0;
  DirectionalSearch engine;
  for (int trial = 0; trial < 10; ++trial) {
    const World w = random_sphere_world(r);
    const Problem p = problem(Vec3(4000, 5000, 2000), Vec3(27000, 26000, 7000), r.uniform(-kPi, kPi));
    if (w.point_collides(p.uav.start, 10) || w.point_collides(p.goal, 10)) continue;
    DirectionalQuery q = planner.query_for(p, w);
    for (const bool relaxed : {false, true}) {
      q.relaxed_heuristic = relaxed;
      q.incumbent_weight = 1.0;
      const DirectionalRoute alone = engine.run(w, q, {});
      q.incumbent_weight = 1.2;
      const DirectionalRoute bounded = engine.run(w, q, {});
      ASSERT_EQ(alone.solved(), bounded.solved()) << trial << ": " << alone.message << " | " << bounded.message;
      if (!alone.solved()) continue;
      EXPECT_LE(bounded.length_m, alone.length_m + 1e-6) << trial;
      EXPECT_EQ(bounded.waypoints.front(), p.uav.start);
      EXPECT_EQ(bounded.waypoints.back(), p.goal);
      EXPECT_TRUE(check_route_limits(bounded.waypoints, p.uav).empty());
      (relaxed ? reverse_alone : cells_alone) += relaxed ? alone.relaxed_expanded : alone.cells_opened;
      (relaxed ? reverse_bounded : cells_bounded) += relaxed ? bounded.relaxed_expanded : bounded.cells_opened;
      solved += relaxed ? 0 : 1;
    }
  }
  EXPECT_GT(solved, 5);
  EXPECT_LT(3 * cells_bounded, 2 * cells_alone);
  // Started again, the reverse search would close nearly twice the points.
  EXPECT_LT(4 * reverse_bounded, 5 * reverse_alone);
}

// Where the exact search runs out of expansions after the first search found a route, that route
// (at most 1.2 times the optimum) is the answer, not a failure.
TEST(DirectionalAStar, TheFirstRouteStandsWhenTheExactSearchRunsOut) {
  Rng r(83);
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  int checked = 0;
  DirectionalSearch engine;
  for (int trial = 0; trial < 10 && checked < 3; ++trial) {
    const World w = random_sphere_world(r);
    const Problem p = problem(Vec3(4000, 5000, 2000), Vec3(27000, 26000, 7000), r.uniform(-kPi, kPi));
    if (w.point_collides(p.uav.start, 10) || w.point_collides(p.goal, 10)) continue;
    DirectionalQuery q = planner.query_for(p, w);
    q.incumbent_weight = 1.0;
    const DirectionalRoute exact = engine.run(w, q, {});
    q.heuristic_weight = 1.2;
    const DirectionalRoute first = engine.run(w, q, {});
    if (!exact.solved() || first.expanded * 2 >= exact.expanded) continue;
    q.heuristic_weight = 1.0;
    q.max_expansions = static_cast<std::int64_t>(first.expanded + 1);
    const DirectionalRoute short_exact = engine.run(w, q, {});
    EXPECT_FALSE(short_exact.solved());
    q.incumbent_weight = 1.2;
    const DirectionalRoute bounded = engine.run(w, q, {});
    ASSERT_TRUE(bounded.solved()) << bounded.message;
    EXPECT_NEAR(bounded.length_m, first.length_m, 1e-6);
    EXPECT_LE(bounded.length_m, 1.2 * exact.length_m + 1e-6);
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

// A goal caged in by six walls: no lattice point has a clear last segment to it, so the relaxed
// distance is infinite everywhere and the search ends after the start's children; with the
// Euclidean bound alone it searches every state it can reach first.
TEST(DirectionalAStar, RelaxedHeuristicEndsAtOnceWhenTheGoalIsCaged) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(30000, 30000, 10000)};
  const Vec3 lo(18000, 18000, 3000), hi(24000, 24000, 9000);  // the cage's inside
  const double t = 500;                                       // wall thickness
  ws.obstacles.push_back(Box{Vec3(lo.x() - t, lo.y() - t, lo.z() - t), Vec3(hi.x() + t, hi.y() + t, lo.z())});
  ws.obstacles.push_back(Box{Vec3(lo.x() - t, lo.y() - t, hi.z()), Vec3(hi.x() + t, hi.y() + t, hi.z() + t)});
  ws.obstacles.push_back(Box{Vec3(lo.x() - t, lo.y() - t, lo.z()), Vec3(lo.x(), hi.y() + t, hi.z())});
  ws.obstacles.push_back(Box{Vec3(hi.x(), lo.y() - t, lo.z()), Vec3(hi.x() + t, hi.y() + t, hi.z())});
  ws.obstacles.push_back(Box{Vec3(lo.x(), lo.y() - t, lo.z()), Vec3(hi.x(), lo.y(), hi.z())});
  ws.obstacles.push_back(Box{Vec3(lo.x(), hi.y(), lo.z()), Vec3(hi.x(), hi.y() + t, hi.z())});
  const World w(std::move(ws));
  // The goal between lattice points, more than a last hop (1.5 L + 1 cells) from every wall
  // point outside: 21.5 km, 6 km, with 1 km cells and L = 2.5.
  const Problem p = problem(Vec3(4000, 5000, 2000), Vec3(21000, 21000, 6000), 0.0);
  const DirectionalAStarPlanner relaxed(
      DirectionalAStarOptions::from_params({{"cell_m", "1000"}, {"relaxed_heuristic", "true"}}));
  const DirectionalAStarPlanner plain(DirectionalAStarOptions::from_params({{"cell_m", "1000"}}));
  const PlanResult a = relaxed.plan(p, w, {});
  const PlanResult b = plain.plan(p, w, {});
  EXPECT_NE(a.status, Status::solved);
  EXPECT_NE(b.status, Status::solved);
  EXPECT_NE(a.message.find("even without the turn limits"), std::string::npos) << a.message;
  EXPECT_LE(a.stats.nodes_expanded, 2u);  // the start, in the first search and the exact one
  EXPECT_GT(b.stats.nodes_expanded, 1000u);
}

// A world less than a cell high has a one-level lattice: it lies at the start's height, so a
// route flies there (it used to drop to the floor of the world and climb back at the goal).
// One engine, two starts at different heights: each route keeps its own (the clearance cache
// belongs to one lattice).
TEST(DirectionalAStar, AOneLevelLatticeLiesAtTheStartsHeight) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(5000, 3000, 60)};
  ws.obstacles.push_back(Box{Vec3(2400, 0, 0), Vec3(2600, 2300, 100)});
  const World w(std::move(ws));
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params({{"cell_m", "100"}}));
  DirectionalSearch search;
  for (const double z : {30.0, 50.0, 12.5}) {
    const Problem p = problem(Vec3(300, 300, z), Vec3(4700, 300, z), std::nullopt);
    const DirectionalRoute r = search.run(w, planner.query_for(p, w), {});
    ASSERT_TRUE(r.solved()) << r.message;
    for (const Vec3& pt : r.waypoints) EXPECT_DOUBLE_EQ(pt.z(), z);
    EXPECT_GT(r.length_m, 2 * std::hypot(2200.0, 2000.0) - 1.0);  // around the wall's end at y = 2300
  }
}

TEST(DirectionalAStar, ParametersAreChecked) {
  EXPECT_THROW(DirectionalAStarOptions::from_params({{"directions", "0"}}), std::invalid_argument);
  EXPECT_THROW(DirectionalAStarOptions::from_params({{"step", "2"}}), std::invalid_argument);
  EXPECT_THROW(DirectionalAStarOptions::from_params({{"incumbent_weight", "0.9"}}), std::invalid_argument);
}

}  // namespace
}  // namespace uavplan
