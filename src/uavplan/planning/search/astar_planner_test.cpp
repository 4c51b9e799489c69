#include "uavplan/planning/search/astar_planner.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"
#include "uavplan/core/units.h"

namespace uavplan {
namespace {

// Boxes and spheres at random in a world of `height` (0: a 2-D world).
World random_world(Rng& r, double height) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(120, 90, height)};
  for (int i = 0; i < 30; ++i) {
    const Vec3 c(r.uniform(10, 110), r.uniform(10, 80), height > 0 ? r.uniform(0, height) : 0.0);
    if (i % 2)
      ws.obstacles.push_back(Sphere{c, r.uniform(2, 8)});
    else
      ws.obstacles.push_back(Box{c - Vec3(r.uniform(1, 9), r.uniform(1, 9), 12), c + Vec3(r.uniform(1, 9), 2, 12)});
  }
  // A wall across the middle with a gap at one end: every route searches.
  ws.obstacles.push_back(Box{Vec3(58, 12, -5), Vec3(62, 90, height + 5)});
  return World(std::move(ws));
}

TEST(AStarPlanner, JumpPointsWhereTheLatticeIsOctile) {
  const VoxelGrid cubes(Aabb{Vec3(0, 0, 0), Vec3(40, 40, 20)}, Vec3(2, 2, 2));
  const VoxelGrid layers(Aabb{Vec3(0, 0, 0), Vec3(40, 40, 20)}, Vec3(2, 2, 1));
  const VoxelGrid plane(Aabb{Vec3(0, 0, 0), Vec3(40, 40, 0)}, Vec3(2, 2, 2));
  const VoxelGrid oblong(Aabb{Vec3(0, 0, 0), Vec3(40, 30, 0)}, Vec3(2, 4, 2));
  EXPECT_EQ(grid_engine(cubes, kPi / 2, true), GridEngine::jps3d);
  EXPECT_EQ(grid_engine(cubes, deg_to_rad(60), true), GridEngine::astar);  // no vertical moves
  EXPECT_EQ(grid_engine(layers, kPi / 2, true), GridEngine::astar);        // not cubes
  EXPECT_EQ(grid_engine(plane, deg_to_rad(10), true), GridEngine::jps2d);  // one layer: no climbing
  EXPECT_EQ(grid_engine(oblong, kPi / 2, true), GridEngine::astar);
  EXPECT_EQ(grid_engine(cubes, kPi / 2, false), GridEngine::astar);
}

// JPS and A* are both optimal on the same grid: the grid routes they find have one length, in
// 3-D and in 2-D, and both plans pass the planner's own segment rule after shortcuts.
TEST(AStarPlanner, JumpPointSearchFindsAStarsLengths) {
  Rng r(17);
  int searched = 0;
  for (int w = 0; w < 12; ++w) {
    const double height = w % 3 == 0 ? 0.0 : 40.0;
    const World world = random_world(r, height);
    Problem pb;
    pb.uav.radius_m = 0.5;
    pb.uav.start = Vec3(2, r.uniform(2, 88), height > 0 ? r.uniform(1, 39) : 0.0);
    pb.goal = Vec3(118, r.uniform(2, 88), height > 0 ? r.uniform(1, 39) : 0.0);
    Params params{{"cell_m", "1"}};
    const PlanResult jps = AStarPlanner(AStarOptions::from_params(params)).plan(pb, world, {});
    params["jump_points"] = "false";
    const PlanResult astar = AStarPlanner(AStarOptions::from_params(params)).plan(pb, world, {});
    ASSERT_EQ(jps.status, astar.status) << "world " << w;
    if (!jps.solved() || astar.stats.nodes_expanded == 0) continue;  // straight: no search
    ++searched;
    EXPECT_NEAR(jps.stats.grid_route_m, astar.stats.grid_route_m, 1e-6) << "world " << w;
  }
  EXPECT_GE(searched, 6);
}

}  // namespace
}  // namespace uavplan
