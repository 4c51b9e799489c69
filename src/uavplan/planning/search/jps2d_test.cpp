#include "uavplan/planning/search/jps2d.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// Random grids of nx0 + trial % nx_mod by ny0 + trial % ny_mod cells, blocked with a density
// drawn from [density_lo, density_lo + density_span): JPS finds A*'s cost, and its expanded path
// is a chain of legal grid moves of that length.
struct RandomGrids {
  std::uint64_t seed;
  int trials, nx0, nx_mod, ny0, ny_mod;
  double density_lo, density_span;
};

void expect_same_cost_as_astar(const RandomGrids& o) {
  Rng r(o.seed);
  for (int trial = 0; trial < o.trials; ++trial) {
    BitGrid g(o.nx0 + trial % o.nx_mod, o.ny0 + trial % o.ny_mod, 1);
    const double density = o.density_lo + o.density_span * r.uniform01();
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < density);
    GridAStar astar(g, bounding_box_moves(g), GridHeuristic::octile);
    Jps2d jps(g);
    for (int q = 0; q < 5; ++q) {
      const std::int64_t s = r.uniform_int(0, g.size() - 1), t = r.uniform_int(0, g.size() - 1);
      const GridSearchResult a = astar.search(s, t), j = jps.search(s, t);
      ASSERT_EQ(a.solved(), j.solved()) << "trial " << trial;
      if (!a.solved()) continue;
      ASSERT_NEAR(a.cost, j.cost, 1e-9) << "trial " << trial;
      const auto cells = jps.expand_path(j.cells);
      ASSERT_EQ(cells.front(), s);
      ASSERT_EQ(cells.back(), t);
      double len = 0.0;
      for (std::size_t i = 1; i < cells.size(); ++i) {
        int x0, y0, x1, y1, k;
        g.coords(cells[i - 1], x0, y0, k);
        g.coords(cells[i], x1, y1, k);
        ASSERT_FALSE(g.blocked(cells[i]));
        if (x0 != x1 && y0 != y1) {
          ASSERT_TRUE(g.free(x1, y0, 0) && g.free(x0, y1, 0)) << "corner cut";
        }
        len += octile_distance(x1 - x0, y1 - y0, 0);
      }
      ASSERT_NEAR(len, j.cost, 1e-9);
    }
  }
}

TEST(Jps2d, SameCostAsAStarOnRandomGrids) { expect_same_cost_as_astar({31, 300, 40, 7, 30, 5, 0.05, 0.4}); }

// Wide, sparse grids: straight jumps run over several 64-cell words, in all four directions.
TEST(Jps2d, SameCostAsAStarWhereJumpsCrossWords) { expect_same_cost_as_astar({32, 60, 150, 11, 140, 13, 0.01, 0.1}); }

// JPS+ reads its jumps from the table: the same jump points as scanning, so the same searches,
// expansion for expansion, goals anywhere (on a jump's line, across a diagonal, at a wall).
TEST(Jps2d, TheTableGivesTheSameSearchesAsScanning) {
  Rng r(33);
  for (int trial = 0; trial < 80; ++trial) {
    BitGrid g(trial % 2 ? 150 + trial % 11 : 20 + trial % 9, 30 + trial % 17 * 7, 1);
    const double density = 0.01 + 0.35 * r.uniform01();
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < density);
    Jps2d scan(g), table(g);
    table.precompute();
    ASSERT_TRUE(table.precomputed());
    for (int q = 0; q < 20; ++q) {
      const std::int64_t s = r.uniform_int(0, g.size() - 1), t = r.uniform_int(0, g.size() - 1);
      const GridSearchResult a = scan.search(s, t), b = table.search(s, t);
      ASSERT_EQ(a.solved(), b.solved()) << "trial " << trial;
      ASSERT_EQ(a.cells, b.cells) << "trial " << trial;
      ASSERT_EQ(a.expanded, b.expanded) << "trial " << trial;
      ASSERT_EQ(a.generated, b.generated) << "trial " << trial;
    }
  }
}

// The table's 16-bit steps reach across the widest grid it is built for, in every direction,
// with pillars making jump points along the way and gaps in a wall making diagonals stop; a grid
// one cell wider gets no table and is searched by scanning, with the same result.
TEST(Jps2d, TheTableSpansTheWidestGridItIsBuiltFor) {
  for (const int width : {JumpTable::kMaxSide, JumpTable::kMaxSide + 1}) {
    BitGrid g(width, 5, 1);
    for (int x = 1000; x < width - 1000; x += 9000) g.set_blocked(g.index(x, 0, 0));  // pillars below row 1
    for (int x = 0; x < width; ++x)
      if (x % 7000 != 3) g.set_blocked(g.index(x, 3, 0));  // a wall with gaps between rows 2 and 4
    Jps2d scan(g), table(g);
    EXPECT_EQ(table.precompute(), width <= JumpTable::kMaxSide);
    EXPECT_EQ(table.precomputed(), width <= JumpTable::kMaxSide);
    const std::int64_t pairs[3][2] = {{g.index(0, 1, 0), g.index(width - 1, 1, 0)},
                                      {g.index(width - 1, 2, 0), g.index(0, 4, 0)},
                                      {g.index(0, 4, 0), g.index(width - 2, 0, 0)}};
    for (const auto& p : pairs) {
      const GridSearchResult a = scan.search(p[0], p[1]), b = table.search(p[0], p[1]);
      ASSERT_TRUE(a.solved());
      EXPECT_EQ(a.cells, b.cells);
      EXPECT_EQ(a.expanded, b.expanded);
      EXPECT_NEAR(a.cost, b.cost, 1e-9);
    }
    EXPECT_NEAR(scan.search(pairs[0][0], pairs[0][1]).cost, width - 1, 1e-6);
  }
}

TEST(Jps2d, RejectsThreeDimensionalGrids) { EXPECT_THROW(Jps2d(BitGrid(4, 4, 2)), std::invalid_argument); }

}  // namespace
}  // namespace uavplan
