// Take-off and landing from the ground, min_agl and clearance through the whole pipeline:
// planned, verified and measured.
#include <gtest/gtest.h>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/core/units.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {
namespace {

// UAVs standing on the ground (terrain and floor) lift off and land vertically, keep min_agl in
// between, and two sent to one landing spot touch down apart.
TEST(GroundOps, GroundStartsAndGoalsTakeOffAndLandApart) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 200, 60)};
  ws.terrain = TerrainGrid(Vec2(0, 0), 50.0, 4, 4, {0, 2, 4, 6, 0, 3, 6, 9, 1, 4, 8, 12, 0, 2, 4, 6});
  ws.obstacles.push_back(Box{Vec3(90, 60, 0), Vec3(110, 140, 35)});
  Scenario sc;
  sc.world = World(std::move(ws));
  for (int i = 0; i < 2; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = Vec3(20, 60 + 80 * i, sc.world.ground_z(20, 60 + 80 * i));
    u.goal = Vec3(180, 100, sc.world.ground_z(180, 100));
    u.speed = {0, 5, 5};
    u.max_climb_rad = deg_to_rad(30);
    u.min_agl_m = 8;
    u.clearance_m = 1;
    sc.uavs.push_back(u);
  }
  sc.mission.separation_m = 5;
  MissionOptions opt;
  opt.params = {{"cell_m", "4"}};
  Plan p = plan_mission(sc, opt);
  ASSERT_EQ(p.status, Status::solved) << p.message;
  for (std::size_t i = 0; i < 2; ++i) {
    const Trajectory& tr = p.uavs[i].trajectory;
    EXPECT_EQ(tr.front().p, sc.uavs[i].start);
    EXPECT_EQ(tr.front().t_s, 0.0);
    EXPECT_TRUE(sc.world.on_ground(tr.back().p));
    std::size_t k = 1;  // the first rows climb straight up
    while (tr[k].p.head<2>() == tr[0].p.head<2>()) ++k;
    EXPECT_GE(tr[k - 1].p.z() - sc.world.ground_z(20, tr[0].p.y()), 8.0 + 1.5);
  }
  EXPECT_GE((p.uavs[0].trajectory.back().p - p.uavs[1].trajectory.back().p).norm(), 5.0);
  EXPECT_TRUE(verify_plan(sc, p).empty()) << describe(verify_plan(sc, p).front());
  compute_metrics(sc, p);
  EXPECT_LE(p.uavs[0].metrics.at("max_climb_deg"), 30.0 + 1e-6);
  EXPECT_GE(p.uavs[0].metrics.at("min_agl_m"), 8.0 - 1e-6);
}

}  // namespace
}  // namespace uavplan
