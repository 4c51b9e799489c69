#include "uavplan/io/movingai.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <tuple>

#include "uavplan/core/rng.h"
#include "uavplan/io/input_error.h"
#include "uavplan/planning/voxel_grid.h"

namespace uavplan {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(MovingAi, Reads2dMapsWithCarriageReturns) {
  const auto path = write_temp("t.map", "type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.@G\r\nT.S\r\n");
  const BitGrid g = read_movingai_map(path);
  EXPECT_EQ(g.nx(), 3);
  EXPECT_EQ(g.ny(), 2);
  EXPECT_FALSE(g.blocked(0, 0, 0));
  EXPECT_TRUE(g.blocked(1, 0, 0));
  EXPECT_FALSE(g.blocked(2, 0, 0));
  EXPECT_TRUE(g.blocked(0, 1, 0));
  EXPECT_FALSE(g.blocked(2, 1, 0));
}

TEST(MovingAi, Reads2dScenarios) {
  const auto path = write_temp("t.scen", "version 1\n3\tt.map\t3\t2\t0\t0\t2\t1\t2.41421356\n");
  const auto p = read_movingai_scen(path);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].bucket, 3);
  EXPECT_EQ(p[0].goal[0], 2);
  EXPECT_EQ(p[0].goal[1], 1);
  EXPECT_DOUBLE_EQ(p[0].optimal, 2.41421356);
}

TEST(MovingAi, Reads3dMapsAndScenarios) {
  const auto map = write_temp("t.3dmap", "voxel 4 3 2\n1 2 1\n3 0 0\n");
  const BitGrid g = read_movingai_3dmap(map);
  EXPECT_EQ(g.nz(), 2);
  EXPECT_TRUE(g.blocked(1, 2, 1));
  EXPECT_TRUE(g.blocked(3, 0, 0));
  EXPECT_FALSE(g.blocked(0, 0, 0));
  const auto scen = write_temp("t.3dscen", "version 1\nt.3dmap\n0 0 0 2 2 1 120.5 1.1\n");
  const auto p = read_movingai_3dscen(scen);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].goal[2], 1);
  EXPECT_EQ(p[0].bucket, 12);
  // Costs no bucket can hold (found by fuzzing: the cast overflowed).
  const auto odd =
      read_movingai_3dscen(write_temp("odd.3dscen", "version 1\nt.3dmap\n0 0 0 1 1 1 1e14 1\n0 0 0 1 1 1 -5 1\n"));
  ASSERT_EQ(odd.size(), 2u);
  for (const auto& q : odd) EXPECT_EQ(q.bucket, -1);
}

TEST(MovingAi, BadFilesNameTheLine) {
  try {
    read_movingai_3dmap(write_temp("bad.3dmap", "voxel 2 2 2\n0 0 0\n5 0 0\n"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_movingai_map(write_temp("bad.map", "type octile\nheight 2\nwidth 3\nmap\n...\n")), InputError);
  EXPECT_THROW(read_movingai_scen(write_temp("bad.scen", "version 1\n1\tx\t3\n")), InputError);
}

// A map made a world of boxes (merge_blocked_cells, each cell in one box) is voxelised, for a
// point UAV on the map's cells, into the map itself: every cell beside a wall stays free.
TEST(MovingAi, BoxesOfAMapVoxeliseBackIntoIt) {
  Rng r(3);
  for (const auto& [nx, ny, nz] : {std::tuple{23, 17, 9}, std::tuple{40, 31, 1}}) {
    BitGrid map(nx, ny, nz);
    for (std::int64_t c = 0; c < map.size(); ++c)
      if (r.uniform01() < 0.35) map.set_blocked(c);
    for (int j = 3; j < 14; ++j) map.set_blocked(map.index(5, j, 0));  // a wall: runs to merge
    const std::vector<CellBox> boxes = merge_blocked_cells(map);
    WorldSpec ws;
    ws.bounds = Aabb{Vec3::Zero(), Vec3(nx, ny, nz > 1 ? nz : 0)};
    std::int64_t volume = 0;
    for (const CellBox& b : boxes) {
      const double lo_z = nz > 1 ? b.min[2] : -1.0, hi_z = nz > 1 ? b.max[2] : 1.0;
      ws.obstacles.push_back(Box{Vec3(b.min[0], b.min[1], lo_z), Vec3(b.max[0], b.max[1], hi_z)});
      volume += static_cast<std::int64_t>(b.max[0] - b.min[0]) * (b.max[1] - b.min[1]) * (b.max[2] - b.min[2]);
    }
    std::int64_t blocked = 0;
    for (std::int64_t c = 0; c < map.size(); ++c) blocked += map.blocked(c);
    EXPECT_EQ(volume, blocked);  // no cell in two boxes
    EXPECT_LT(boxes.size(), static_cast<std::size_t>(blocked));
    const World world(std::move(ws));
    const VoxelGrid g = voxelize(world, Vec3(1, 1, 1), 1e-3, 1e9, {}, CellRule::lattice);
    ASSERT_EQ(g.size(), map.size());
    for (std::int64_t c = 0; c < map.size(); ++c) ASSERT_EQ(g.blocked(c), map.blocked(c)) << "cell " << c;
  }
}

}  // namespace
}  // namespace uavplan
