#include "uavplan/coordination/spacetime/uav_lattice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "uavplan/coordination/spacetime/mapf.h"
#include "uavplan/coordination/spacetime/space_time_astar.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {
namespace {

constexpr double kNeed = 5.0;

// A 40 x 40 x 12 m world with a tower in the middle; cells of 4 m (below the separation, so a
// UAV keeps several vertices round it) and three points of UAVs off the lattice.
struct Fixture {
  World world{
      WorldSpec{Aabb{Vec3(0, 0, 0), Vec3(40, 40, 12)}, {Box{Vec3(16, 16, 0), Vec3(24, 24, 12)}}, {}, {}, {}, {}, {}}};
  std::vector<Vec3> points{Vec3(1.3, 2.1, 5.2), Vec3(38.5, 37.0, 6.1), Vec3(20.2, 3.3, 4.4)};
  UavLattice lattice;
  Fixture() {
    UavLatticeOptions o;
    o.cell_m = 4.0;
    o.body_m = 0.5;
    o.need_m = kNeed;
    lattice = build_uav_lattice(world, points, o, StopCondition{});
  }
  Trajectory flight(const SpaceTimePath& p) const {
    Trajectory tr;
    for (std::size_t t = 0; t < p.size(); ++t) tr.push_back({static_cast<double>(t), lattice.position[p[t]]});
    return tr;
  }
  // A random walk on the graph, waits included, from a random vertex with neighbours.
  SpaceTimePath walk(std::mt19937& rng, int steps, int from = -1) const {
    const SpaceTimeGraph& g = lattice.graph;
    std::uniform_int_distribution<int> any(0, g.vertex_count - 1);
    int v = from >= 0 ? from : any(rng);
    while (g.degree(v) == 0) v = any(rng);
    SpaceTimePath p{v};
    for (int s = 0; s < steps; ++s) {
      std::uniform_int_distribution<int> pick(0, g.degree(v));  // degree: wait
      const int k = pick(rng);
      if (k < g.degree(v)) v = g.next[g.first[v] + k];
      p.push_back(v);
    }
    return p;
  }
};

bool conflict_brute(const Fixture& f, const std::vector<SpaceTimePath>& paths) {
  for (std::size_t a = 0; a < paths.size(); ++a)
    for (std::size_t b = a + 1; b < paths.size(); ++b)
      if (closest_approach(f.flight(paths[a]), f.flight(paths[b])).distance_m < kNeed) return true;
  return false;
}

TEST(UavLattice, EdgesKeepOffObstaclesAndPointsJoinTheLattice) {
  const Fixture f;
  const SpaceTimeGraph& g = f.lattice.graph;
  for (int v = 0; v < g.vertex_count; ++v)
    for (int k = g.first[v]; k < g.first[v + 1]; ++k)
      ASSERT_TRUE(f.world.segment_valid(f.lattice.position[v], f.lattice.position[g.next[k]], 0.5));
  for (std::size_t i = 0; i < f.points.size(); ++i) EXPECT_GT(g.degree(f.lattice.point_vertex(i)), 0);
}

// Alone (nothing forbidden) under a weaker heuristic than the exact distances, the search still
// finds the shortest path: a vertex reached late first and early later keeps the early time.
TEST(UavLattice, AloneTheSearchIsShortestUnderABound) {
  const Fixture f;
  const SpaceTimeGraph& g = f.lattice.graph;
  std::mt19937 rng(4);
  SpaceTimeSearch search;
  SpaceTimeTable none;
  none.clear(g.vertex_count);
  const int cells = f.lattice.cell_count();
  for (int k = 0; k < 200; ++k) {
    int s = static_cast<int>(rng() % cells), t = static_cast<int>(rng() % cells);
    if (g.degree(s) == 0 || g.degree(t) == 0) continue;
    const std::vector<int> exact = distances_to(g, t);
    if (exact[s] < 0) continue;
    std::vector<int> bound(exact.size(), -1);  // Chebyshev cells less one: consistent, not exact
    for (int v = 0; v < g.vertex_count; ++v)
      if (exact[v] >= 0)
        bound[v] =
            std::max(0, static_cast<int>(std::lround(
                            (f.lattice.position[v] - f.lattice.position[t]).cwiseAbs().maxCoeff() / f.lattice.cell_m)) -
                            1);
    const SpaceTimeQuery q{s, t, &bound, &none, nullptr, 1.0};
    const SpaceTimeAnswer a = search.find(g, q, StopCondition{});
    ASSERT_TRUE(a.found) << k;
    ASSERT_EQ(a.cost, exact[s]) << k;
  }
}

// The scan's conflicts are the trajectories' closest approaches below the separation: walks
// through points and lattice, compared with the exact pairwise distance.
TEST(UavLattice, ConflictsAreTheTrajectoriesClosestApproach) {
  const Fixture f;
  const LatticeAgents agents(f.lattice, {}, kNeed);
  std::mt19937 rng(5);
  int with = 0;
  for (int k = 0; k < 1500; ++k) {
    std::vector<SpaceTimePath> paths;
    for (int a = 0; a < 3; ++a)  // every third set has one walk from a UAV's point
      paths.push_back(f.walk(rng, 4 + k % 9, a == 0 && k % 3 == 0 ? f.lattice.point_vertex(k / 3 % 3) : -1));
    const bool brute = conflict_brute(f, paths);
    with += brute;
    ASSERT_EQ(agents.first_conflict(paths).has_value(), brute) << k;
    ASSERT_EQ(agents.count_conflicts(paths) > 0, brute) << k;
  }
  EXPECT_GT(with, 100);
  EXPECT_LT(with, 1400);
}

// What a path puts in a table is met by another path exactly when the two conflict.
TEST(UavLattice, TableEntriesAreTheConflicts) {
  const Fixture f;
  const LatticeAgents agents(f.lattice, {}, kNeed);
  std::mt19937 rng(9);
  SpaceTimeTable table;
  for (int k = 0; k < 1500; ++k) {
    const SpaceTimePath a = f.walk(rng, 3 + k % 7, k % 4 == 0 ? f.lattice.point_vertex(k / 4 % 3) : -1);
    const SpaceTimePath b = f.walk(rng, 3 + k % 5, k % 4 == 1 ? f.lattice.point_vertex(k / 4 % 3) : -1);
    table.clear(f.lattice.graph.vertex_count);
    agents.add_path(0, a, table);
    bool meets = false;
    const int end = static_cast<int>(std::max(a.size(), b.size()));
    for (int t = 0; t <= end && !meets; ++t)
      meets = table.at(vertex_at(b, t), t) > 0 || table.moves(vertex_at(b, t), vertex_at(b, t + 1), t) > 0;
    ASSERT_EQ(meets, conflict_brute(f, {a, b})) << k;
  }
}

// Moving obstacles (one at a constant velocity, one on a path with corners and an end) forbid a
// walk exactly when its trajectory comes nearer their surfaces than the UAV's radius; with the
// corners between ticks (`bent`), whenever it does (the step widened by the corner).
class MovingObstacles : public ::testing::TestWithParam<bool> {};
TEST_P(MovingObstacles, ForbidWhatComesNear) {
  const bool bent = GetParam();
  Fixture f;
  MovingObstacle linear{"m1", 2.0, Vec3(0, 20, 6), Vec3(2.5, 0.3, 0.0), {}};
  MovingObstacle path{"m2",
                      1.5,
                      Vec3::Zero(),
                      Vec3::Zero(),
                      {{0.0, Vec3(30, 5, 4)}, {bent ? 3.5 : 3.0, Vec3(30, 30, 8)}, {bent ? 6.2 : 6.0, Vec3(8, 30, 8)}}};
  WorldSpec ws = f.world.spec();
  ws.moving = {linear, path};
  const World with(ws);
  LatticeAgents agents(f.lattice, {}, kNeed);
  agents.keep_off_moving(ws.moving, 0.5, 0.0, 1.0);
  const SpaceTimeTable& table = *agents.moving();
  std::mt19937 rng(12);
  int near = 0;
  for (int k = 0; k < 1500; ++k) {
    const SpaceTimePath b = f.walk(rng, 4 + k % 9);
    bool meets = false;
    for (int t = 0; t <= 30 && !meets; ++t)
      meets = table.at(vertex_at(b, t), t) > 0 || table.moves(vertex_at(b, t), vertex_at(b, t + 1), t) > 0;
    Trajectory tr = f.flight(b);
    tr.push_back({30.0, tr.back().p});  // it stays where it ended
    const bool brute = closest_moving_approach(with, tr).distance_m < 0.5 + kMovingMargin_m;
    near += brute;
    if (bent)
      ASSERT_TRUE(meets || !brute) << k;
    else
      ASSERT_EQ(meets, brute) << k;
  }
  EXPECT_GT(near, 50);
}
INSTANTIATE_TEST_SUITE_P(UavLattice, MovingObstacles, ::testing::Bool());

// Six UAVs swapping across a circle: every method finds a plan whose trajectories keep apart.
TEST(UavLattice, SixUavSwapIsSolvedByEveryMethod) {
  const World world{WorldSpec{Aabb{Vec3(0, 0, 0), Vec3(100, 100, 20)}, {}, {}, {}, {}, {}, {}}};
  std::vector<Vec3> points;
  for (int i = 0; i < 6; ++i) {
    const double a = 2.0 * kPi * i / 6.0;
    points.emplace_back(50 + 40 * std::cos(a), 50 + 40 * std::sin(a), 10);
  }
  UavLatticeOptions o;
  o.need_m = kNeed;
  const UavLattice l = build_uav_lattice(world, points, o, StopCondition{});
  std::vector<LatticeAgent> list;
  for (int i = 0; i < 6; ++i) list.push_back({l.point_vertex(i), {l.point_vertex((i + 3) % 6)}});
  const LatticeAgents agents(l, list, kNeed);
  for (const MapfMethod m : {MapfMethod::prioritized, MapfMethod::ecbs, MapfMethod::cbs}) {
    MapfOptions mo;
    mo.method = m;
    const MapfResult r = solve_space_time(agents, mo);
    ASSERT_TRUE(r.solved()) << to_string(m) << ": " << r.message;
    for (int i = 0; i < 6; ++i) {
      EXPECT_EQ(r.paths[i].front(), l.point_vertex(i));
      EXPECT_EQ(r.paths[i].back(), l.point_vertex((i + 3) % 6));
      for (int j = i + 1; j < 6; ++j) {
        Trajectory a, b;
        for (int t = 0; t <= r.makespan; ++t) {
          a.push_back({1.0 * t, l.position[vertex_at(r.paths[i], t)]});
          b.push_back({1.0 * t, l.position[vertex_at(r.paths[j], t)]});
        }
        EXPECT_GE(closest_approach(a, b).distance_m, kNeed) << to_string(m) << " " << i << " " << j;
      }
    }
  }
}

}  // namespace
}  // namespace uavplan
