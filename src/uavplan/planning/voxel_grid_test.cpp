#include "uavplan/planning/voxel_grid.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"
#include "uavplan/planning/search/grid_astar.h"

namespace uavplan {
namespace {

World test_world(Rng& r) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(100, 80, 30)};
  for (int i = 0; i < 40; ++i) {
    const Vec3 c(r.uniform(0, 100), r.uniform(0, 80), r.uniform(0, 30));
    if (i % 2)
      ws.obstacles.push_back(Sphere{c, r.uniform(1, 6)});
    else
      ws.obstacles.push_back(Prism{{{c.x(), c.y()}, {c.x() + 5, c.y() + 1}, {c.x() + 1, c.y() + 6}}, 0, c.z()});
  }
  std::vector<double> h(10 * 8);
  for (auto& x : h) x = r.uniform(0, 6);
  ws.terrain = TerrainGrid(Vec2(0, 0), 10.0, 10, 8, std::move(h));
  return World(std::move(ws));
}

TEST(VoxelGrid, TilesTheBoundsExactly) {
  const VoxelGrid g(Aabb{Vec3(0, 0, 0), Vec3(10, 7, 0)}, Vec3(3, 3, 3));
  EXPECT_EQ(g.nx(), 3);
  EXPECT_EQ(g.ny(), 2);
  EXPECT_EQ(g.nz(), 1);  // a 2-D world has one layer
  EXPECT_NEAR(g.cell().x(), 10.0 / 3, 1e-12);
  EXPECT_NEAR(g.center(2, 1, 0).y(), 7.0 * 3 / 4, 1e-12);
}

// Conservative: every point of a free cell is at least the inflation away from the world.
TEST(VoxelGrid, FreeCellsAreSafeEverywhere) {
  Rng r(4);
  const World w = test_world(r);
  const double inflation = 0.7;
  const VoxelGrid g = voxelize(w, Vec3(2.5, 2.5, 1.5), inflation, 25.0);
  int free_cells = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        if (g.blocked(i, j, k)) continue;
        ++free_cells;
        const Vec3 c = g.center(i, j, k);
        ASSERT_LE(c.z(), 25.0);
        for (int s = 0; s < 4; ++s) {
          const Vec3 p = c + 0.5 * g.cell().cwiseProduct(Vec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)));
          ASSERT_GE(w.clearance(p, 10.0), inflation) << "cell " << i << "," << j << "," << k;
        }
      }
  EXPECT_GT(free_cells, g.size() / 3);
}

// The shortcuts (columns under boxes that reach above the grid, terrain columns asked only
// between their floor and reach above their neighbours) block exactly the cells the definition
// does: a centre closer than inflation + half-diagonal to an obstacle or the terrain.
TEST(VoxelGrid, ShortcutsBlockExactlyWhatTheDefinitionBlocks) {
  Rng r(9);
  WorldSpec ws = test_world(r).spec();
  for (int i = 0; i < 30; ++i) {  // a closed sky over a band, as planning_view makes it
    const Vec3 lo(r.uniform(0, 95), r.uniform(0, 75), r.uniform(8, 28));
    ws.obstacles.push_back(Box{lo, Vec3(lo.x() + r.uniform(1, 12), lo.y() + r.uniform(1, 12), 31)});
  }
  const World w(std::move(ws));
  const Vec3 cell(2.5, 2.0, 1.5);
  const double inflation = 0.7, reach = inflation + 0.5 * cell.norm();
  const VoxelGrid g = voxelize(w, cell, inflation, 1e9);
  int blocked = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const Vec3 c = g.center(i, j, k);
        bool near = w.terrain()->point_distance(c, reach) < reach;
        for (const Obstacle& o : w.obstacles()) near = near || point_distance(o, c) < reach;
        ASSERT_EQ(g.blocked(i, j, k), near) << "cell " << i << "," << j << "," << k;
        blocked += near;
      }
  EXPECT_GT(blocked, g.size() / 4);
}

// The lattice rule: every move a grid search may make between free cells (to one of the 26
// neighbours, its bounding box of cells free) keeps the inflation from every obstacle and the
// terrain, though cells beside obstacles are free where the whole-cell rule blocks them.
TEST(VoxelGrid, LatticeMovesBetweenFreeCellsAreSafe) {
  Rng r(12);
  WorldSpec ws = test_world(r).spec();
  for (int i = 0; i < 25; ++i) {
    const Vec3 lo(r.uniform(0, 95), r.uniform(0, 75), r.uniform(0, 28));
    ws.obstacles.push_back(Box{lo, lo + Vec3(r.uniform(0.5, 9), r.uniform(0.5, 9), r.uniform(0.5, 9))});
  }
  const World w(std::move(ws));
  const Vec3 cell(2.5, 2.5, 2.0);
  for (const double inflation : {0.6, 1.7}) {
    const VoxelGrid g = voxelize(w, cell, inflation, 1e9, {}, CellRule::lattice);
    const VoxelGrid whole = voxelize(w, cell, inflation, 1e9);
    std::int64_t free_lattice = 0, free_whole = 0, moves = 0;
    for (std::int64_t c = 0; c < g.size(); ++c) {
      free_lattice += !g.blocked(c);
      free_whole += !whole.blocked(c);
      ASSERT_TRUE(!whole.blocked(c) ? !g.blocked(c) : true) << "the lattice rule blocks more than the whole cell's";
    }
    EXPECT_GT(free_lattice, free_whole);
    for (const GridMove& m : bounding_box_moves(g.cells(), cell.x(), cell.y(), cell.z()))
      for (int k = 0; k < g.nz(); ++k)
        for (int j = 0; j < g.ny(); ++j)
          for (int i = 0; i < g.nx(); ++i) {
            if (m.di + 2 * m.dj + 4 * m.dk < 0 || g.blocked(i, j, k)) continue;  // each move one way
            if ((g.cells().free_mask(i, j, k) & m.need) != m.need) continue;
            const Vec3 a = g.center(i, j, k), b = g.center(i + m.di, j + m.dj, k + m.dk);
            ++moves;
            ASSERT_GE(w.segment_clearance(a, b, 10.0), inflation - 1e-9)
                << "inflation " << inflation << " from " << a.transpose() << " to " << b.transpose();
          }
    EXPECT_GT(moves, 10000);
  }
}

}  // namespace
}  // namespace uavplan
