#include "uavplan/world/world.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

World random_world(int n, Rng& r, bool with_terrain) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 200, 60)};
  for (int i = 0; i < n; ++i) {
    const Vec3 c(r.uniform(0, 200), r.uniform(0, 200), r.uniform(0, 60));
    const double s = r.uniform(1, 8);
    switch (i % 4) {
      case 0:
        ws.obstacles.push_back(Sphere{c, s});
        break;
      case 1:
        ws.obstacles.push_back(Cylinder{c.head<2>(), s, c.z() - s, c.z() + s});
        break;
      case 2:
        ws.obstacles.push_back(Box{c.array() - s, c.array() + 0.5 * s});
        break;
      default:
        ws.obstacles.push_back(Prism{{{c.x(), c.y()}, {c.x() + s, c.y()}, {c.x(), c.y() + s}}, c.z(), c.z() + s});
    }
  }
  if (with_terrain) {
    std::vector<double> h(20 * 20);
    for (auto& x : h) x = r.uniform(0, 15);
    ws.terrain = TerrainGrid(Vec2(0, 0), 10.0, 20, 20, std::move(h));
  }
  return World(std::move(ws));
}

double brute_clearance(const World& w, const Vec3& p) {
  double best = World::kInf;
  for (const auto& o : w.obstacles()) best = std::min(best, point_distance(o, p));
  if (const auto* t = w.terrain())
    for (int j = 0; j < t->ny(); ++j)
      for (int i = 0; i < t->nx(); ++i) best = std::min(best, t->column(i, j).distance(p));
  return best;
}

double brute_segment(const World& w, const Vec3& a, const Vec3& b) {
  double best = World::kInf;
  for (const auto& o : w.obstacles()) best = std::min(best, segment_distance(o, a, b));
  if (const auto* t = w.terrain())
    for (int j = 0; j < t->ny(); ++j)
      for (int i = 0; i < t->nx(); ++i) {
        const Aabb col = t->column(i, j);
        best = std::min(best, golden_section_min([&](double s) { return col.distance(a + s * (b - a)); }, 0.0, 1.0));
      }
  return best;
}

class WorldOracle : public ::testing::TestWithParam<bool> {};

TEST_P(WorldOracle, QueriesMatchBruteForce) {
  Rng r(17);
  const World w = random_world(300, r, GetParam());
  for (int k = 0; k < 400; ++k) {
    const Vec3 a(r.uniform(0, 200), r.uniform(0, 200), r.uniform(0, 60));
    const Vec3 b = a + Vec3(r.normal(), r.normal(), 0.3 * r.normal()) * r.uniform(1, 30);
    const double cap = r.uniform(0.5, 5.0);
    ASSERT_NEAR(w.clearance(a, World::kInf), brute_clearance(w, a), 1e-9);
    const double exact = brute_segment(w, a, b);
    ASSERT_NEAR(w.segment_clearance(a, b, World::kInf), exact, 1e-9);
    ASSERT_NEAR(w.segment_clearance(a, b, cap), std::min(cap, exact), 1e-9);
    ASSERT_EQ(w.segment_collides(a, b, cap), exact < cap);
  }
}

INSTANTIATE_TEST_SUITE_P(WithAndWithoutTerrain, WorldOracle, ::testing::Bool());

TEST(World, TerrainHeightAndCollision) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20, 10, 50)};
  ws.terrain = TerrainGrid(Vec2(0, 0), 10.0, 2, 1, {5.0, 30.0});
  const World w(std::move(ws));
  EXPECT_DOUBLE_EQ(w.terrain()->height_at(5, 5), 5.0);
  EXPECT_DOUBLE_EQ(w.terrain()->height_at(15, 5), 30.0);
  EXPECT_TRUE(std::isinf(w.terrain()->height_at(25, 5)));
  EXPECT_FALSE(w.point_collides(Vec3(5, 5, 6), 0.5));
  EXPECT_TRUE(w.point_collides(Vec3(5, 5, 5.4), 0.5));
  // Flying level at 10 m into the 30 m column.
  EXPECT_TRUE(w.segment_collides(Vec3(2, 5, 10), Vec3(18, 5, 10), 0.5));
  EXPECT_NEAR(w.segment_clearance(Vec3(2, 5, 10), Vec3(9, 5, 10), 100), 1.0, 1e-9);
}

// A cell's lowest ground (an elevation model's lowest pixel in it) is what max_agl is measured
// from; collisions and min_agl keep its height.
TEST(World, HeightAboveTheGroundIsFromACellsLowestPoint) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20, 10, 50)};
  ws.terrain = TerrainGrid(Vec2(0, 0), 10.0, 2, 1, {5.0, 30.0}, {2.0, 31.0});  // a low above its height is its height
  const World w(std::move(ws));
  EXPECT_DOUBLE_EQ(w.terrain()->low(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(w.terrain()->low(1, 0), 30.0);
  EXPECT_NEAR(w.highest_height_above_ground(Vec3(1, 5, 40), Vec3(9, 5, 40)), 38.0, 1e-12);
  EXPECT_NEAR(w.highest_height_above_ground(Vec3(11, 5, 40), Vec3(19, 5, 40)), 10.0, 1e-12);
  EXPECT_NEAR(w.lowest_height_above_ground(Vec3(1, 5, 40), Vec3(9, 5, 40)), 35.0, 1e-12);
  EXPECT_TRUE(w.point_collides(Vec3(5, 5, 5.4), 0.5));
  EXPECT_THROW(TerrainGrid(Vec2(0, 0), 10.0, 2, 1, {5.0, 30.0}, {2.0}), std::invalid_argument);
}

TEST(World, MovingObstacleClearanceIsExactInTime) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-100, -100, 0), Vec3(100, 100, 50)};
  ws.moving.push_back({"m1", 1.0, Vec3(0, -50, 10), Vec3(0, 5, 0)});  // crosses the origin at t = 10
  const World w(std::move(ws));
  // UAV crossing the origin along x at t = 10: they meet.
  EXPECT_NEAR(w.moving_clearance(Vec3(-50, 0, 10), 0.0, Vec3(50, 0, 10), 20.0), -1.0, 1e-9);
  // Same path ten seconds later: the obstacle is 50 m past.
  EXPECT_GT(w.moving_clearance(Vec3(-50, 0, 10), 10.0, Vec3(50, 0, 10), 30.0), 20.0);
}

TEST(World, PathObstacleIsPiecewiseLinearAndItsClearanceExact) {
  // A turning obstacle: east for 10 s, then north for 10 s, then it stays.
  MovingObstacle m{
      "turn", 1.0, Vec3::Zero(), Vec3::Zero(), {{0, Vec3(0, 0, 5)}, {10, Vec3(50, 0, 5)}, {20, Vec3(50, 50, 5)}}};
  EXPECT_EQ(m.position_at(-3), Vec3(0, 0, 5));
  EXPECT_EQ(m.position_at(15), Vec3(50, 25, 5));
  EXPECT_EQ(m.position_at(99), Vec3(50, 50, 5));
  EXPECT_EQ(m.velocity_at(5), Vec3(5, 0, 0));
  EXPECT_EQ(m.velocity_at(10), Vec3(0, 5, 0));
  EXPECT_EQ(m.velocity_at(25), Vec3::Zero());
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-100, -100, 0), Vec3(100, 100, 50)};
  ws.moving.push_back(m);
  const World w(std::move(ws));
  // Against fine sampling on random UAV segments spanning the turn.
  Rng r(5);
  for (int k = 0; k < 200; ++k) {
    const Vec3 a(r.uniform(-20, 80), r.uniform(-20, 80), 5), b(r.uniform(-20, 80), r.uniform(-20, 80), 5);
    const double ta = r.uniform(-5, 15), tb = ta + r.uniform(0.1, 20);
    double sampled = World::kInf;
    for (int i = 0; i <= 20000; ++i) {
      const double f = i / 20000.0, t = ta + f * (tb - ta);
      sampled = std::min(sampled, (a + f * (b - a) - m.position_at(t)).norm() - 1.0);
    }
    const double exact = w.moving_clearance(a, ta, b, tb);
    EXPECT_LE(exact, sampled + 1e-9);
    EXPECT_GE(exact, sampled - 0.01);
  }
}

TEST(World, RejectsInvalidSpecs) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(-1, 1, 1)};
  EXPECT_THROW(World{ws}, std::invalid_argument);
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  ws.obstacles.push_back(Prism{{{0, 0}, {1, 1}}, 0, 1});
  EXPECT_THROW(World{ws}, std::invalid_argument);
  ws.obstacles.clear();
  ws.moving.push_back({"one_row", 1.0, Vec3::Zero(), Vec3::Zero(), {{0, Vec3::Zero()}}});
  EXPECT_THROW(World{ws}, std::invalid_argument);
  ws.moving.back().path = {{0, Vec3::Zero()}, {0, Vec3::Ones()}};
  EXPECT_THROW(World{ws}, std::invalid_argument);
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

// A value is made once per key and shared, by copies of the world too; the oldest beyond
// kMaxValues is dropped; a make() that throws keeps nothing.
TEST(WorldMemo, MakesOnceKeepsTheRecentAndNothingThatFailed) {
  const World w;
  const World copy = w;
  int made = 0;
  const auto make = [&made] { return ++made; };
  const auto a = w.memo().get<int>("a", make);
  EXPECT_EQ(copy.memo().get<int>("a", make), a);
  EXPECT_EQ(made, 1);
  for (std::size_t k = 0; k < WorldMemo::kMaxValues; ++k) w.memo().get<int>("k" + std::to_string(k), make);
  EXPECT_EQ(made, 1 + static_cast<int>(WorldMemo::kMaxValues));
  EXPECT_EQ(*w.memo().get<int>("a", make), made);  // dropped, made again
  EXPECT_THROW(w.memo().get<int>("bad", []() -> int { throw std::runtime_error("no"); }), std::runtime_error);
  EXPECT_EQ(*w.memo().get<int>("bad", [] { return 7; }), 7);
  EXPECT_NE(World().memo().get<int>("a", make), w.memo().get<int>("a", make));  // another world
}

}  // namespace
}  // namespace uavplan
