#include "uavplan/planning/search/jps3d.h"

#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// The path behind a result: starts and ends where asked, every step a legal move (its bounding
// box free), and as long as the cost says.
void expect_legal_path(const BitGrid& g, const Jps3d& jps, const GridSearchResult& r, std::int64_t s, std::int64_t t) {
  const auto cells = jps.expand_path(r.cells);
  ASSERT_EQ(cells.front(), s);
  ASSERT_EQ(cells.back(), t);
  double len = 0.0;
  for (std::size_t i = 1; i < cells.size(); ++i) {
    int a[3], b[3];
    g.coords(cells[i - 1], a[0], a[1], a[2]);
    g.coords(cells[i], b[0], b[1], b[2]);
    for (int x = std::min(a[0], b[0]); x <= std::max(a[0], b[0]); ++x)
      for (int y = std::min(a[1], b[1]); y <= std::max(a[1], b[1]); ++y)
        for (int z = std::min(a[2], b[2]); z <= std::max(a[2], b[2]); ++z) ASSERT_TRUE(g.free(x, y, z)) << "corner cut";
    ASSERT_LE(std::abs(b[0] - a[0]) + std::abs(b[1] - a[1]) + std::abs(b[2] - a[2]), 3);
    len += octile_distance(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
  }
  ASSERT_NEAR(len, r.cost, 1e-9);
}

// Between `queries` random cells of g: JPS finds A*'s cost (or none where A* finds none), on a
// legal path; from both ends in turns (the default) and from the start alone.
void expect_same_cost_as_astar(const BitGrid& g, Rng& r, int queries, int trial) {
  GridAStar astar(g, bounding_box_moves(g), GridHeuristic::octile);
  Jps3d both(g), forward(g, Jps3dOptions{false});
  for (int q = 0; q < queries; ++q) {
    const std::int64_t s = r.uniform_int(0, g.size() - 1), t = r.uniform_int(0, g.size() - 1);
    const GridSearchResult a = astar.search(s, t);
    for (Jps3d* jps : {&both, &forward}) {
      const GridSearchResult j = jps->search(s, t);
      ASSERT_EQ(a.solved(), j.solved()) << "trial " << trial << " query " << q;
      if (!a.solved()) continue;
      ASSERT_NEAR(a.cost, j.cost, 1e-9) << "trial " << trial << " query " << q;
      expect_legal_path(g, *jps, j, s, t);
    }
  }
}

// Random volumes, from nearly empty to nearly walled off, some longer than a bit word along each
// axis: JPS finds A*'s cost (or none where A* finds none) between random cells.
TEST(Jps3d, SameCostAsAStarOnRandomVolumes) {
  Rng r(31);
  for (int trial = 0; trial < 60; ++trial) {
    const int nx = 4 + trial % 7 + (trial % 10 == 3 ? 70 : 0), ny = 3 + trial % 5 + (trial % 10 == 6 ? 66 : 0),
              nz = 2 + trial % 6 + (trial % 10 == 9 ? 65 : 0);
    BitGrid g(nx, ny, nz);
    const double density = 0.45 * r.uniform01();
    for (std::int64_t c = 0; c < g.size(); ++c) g.set_blocked(c, r.uniform01() < density);
    expect_same_cost_as_astar(g, r, 12, trial);
  }
}

// Boxes and slabs in a larger volume (obstacles with faces, edges and corners, the case the
// forced moves are for) rather than scattered cells.
TEST(Jps3d, SameCostAsAStarAmongBoxes) {
  Rng r(47);
  for (int trial = 0; trial < 20; ++trial) {
    BitGrid g(24 + trial % 5, 20 + trial % 3, 16 + trial % 4);
    for (int box = 0; box < 12; ++box) {
      const int x0 = r.uniform_int(0, g.nx() - 1), y0 = r.uniform_int(0, g.ny() - 1), z0 = r.uniform_int(0, g.nz() - 1);
      const int dx = r.uniform_int(1, 8), dy = r.uniform_int(1, 8), dz = r.uniform_int(1, 8);
      for (int z = z0; z < std::min(z0 + dz, g.nz()); ++z)
        for (int y = y0; y < std::min(y0 + dy, g.ny()); ++y)
          for (int x = x0; x < std::min(x0 + dx, g.nx()); ++x) g.set_blocked(g.index(x, y, z));
    }
    expect_same_cost_as_astar(g, r, 20, trial);
  }
}

// A wall across the volume with one hole: the way through the hole is found (its edge forces the
// turn), and in an empty volume the cost is the octile distance with a handful of nodes.
TEST(Jps3d, ThroughAHoleAndAcrossEmptySpace) {
  BitGrid g(30, 30, 30);
  for (int z = 0; z < 30; ++z)
    for (int y = 0; y < 30; ++y)
      if (!(y == 21 && z == 4)) g.set_blocked(g.index(15, y, z));
  Jps3d jps(g);
  GridAStar astar(g, bounding_box_moves(g), GridHeuristic::octile);
  const std::int64_t s = g.index(2, 3, 25), t = g.index(28, 27, 26);
  const GridSearchResult j = jps.search(s, t), a = astar.search(s, t);
  ASSERT_TRUE(j.solved());
  EXPECT_NEAR(j.cost, a.cost, 1e-9);
  expect_legal_path(g, jps, j, s, t);

  BitGrid empty(40, 40, 40);
  Jps3d open(empty);
  const GridSearchResult e = open.search(empty.index(1, 2, 3), empty.index(38, 20, 9));
  ASSERT_TRUE(e.solved());
  EXPECT_NEAR(e.cost, octile_distance(37, 18, 6), 1e-9);
  EXPECT_LE(e.expanded, 10u);
}

// A cage round one end, open on the side away from the other end: the search toward the cage
// closes the whole volume of shortest obstacle-free paths before its f reaches the way round,
// the search out of it turns at once. Either end caged, the race costs a small part of the search
// from the start alone and finds its cost, on a legal path (turned round when the search from
// the goal wins); a stop condition still ends it.
// A shell two cells round c, open on the side +x (open = 1) or -x (-1).
void cage(BitGrid& g, const int c[3], int open) {
  for (int z = c[2] - 2; z <= c[2] + 2; ++z)
    for (int y = c[1] - 2; y <= c[1] + 2; ++y)
      for (int x = c[0] - 2; x <= c[0] + 2; ++x) {
        const bool shell = std::abs(x - c[0]) == 2 || std::abs(y - c[1]) == 2 || std::abs(z - c[2]) == 2;
        if (shell && x != c[0] + 2 * open) g.set_blocked(g.index(x, y, z));
      }
}

TEST(Jps3d, BothEndsInTurnsTakeTheCheaperWay) {
  BitGrid g(64, 56, 48);
  const int c[3] = {50, 42, 34};
  cage(g, c, 1);  // open away from the other end
  const std::int64_t caged = g.index(c[0], c[1], c[2]), far = g.index(3, 4, 5);
  Jps3d both(g), forward(g, Jps3dOptions{false});
  GridAStar astar(g, bounding_box_moves(g), GridHeuristic::octile);
  for (const auto& [s, t] : {std::pair{far, caged}, std::pair{caged, far}}) {
    const GridSearchResult a = astar.search(s, t), one = forward.search(s, t), two = both.search(s, t);
    ASSERT_TRUE(two.solved());
    EXPECT_NEAR(two.cost, a.cost, 1e-9);
    EXPECT_NEAR(one.cost, a.cost, 1e-9);
    expect_legal_path(g, both, two, s, t);
    if (s == far) {
      EXPECT_LT(10 * two.expanded, one.expanded) << one.expanded << " " << two.expanded;
    }
    EXPECT_LE(two.expanded, 2 * std::min(one.expanded, forward.search(t, s).expanded) + 128);
  }
  // Both ends caged, each open away from the other: the stop condition (asked every 1,024
  // expansions of the two together) ends the race.
  const int d[3] = {6, 7, 8};
  cage(g, d, -1);
  const std::int64_t also_caged = g.index(d[0], d[1], d[2]);
  Jps3d again(g);
  const GridSearchResult whole = again.search(also_caged, caged);
  ASSERT_TRUE(whole.solved());
  ASSERT_GT(whole.expanded, 2048u);
  const GridSearchResult cut = again.search(also_caged, caged, StopCondition::iterations(1024));
  EXPECT_EQ(cut.reason, Reason::stopped);
  EXPECT_FALSE(cut.solved());
  EXPECT_EQ(cut.expanded, 1024u);
}

// The argument behind the pruning (jps3d.h): two moves d then e that leave the canonical order
// cost the same as e then d when d is a sub-move of e, and more than the canonical path to the
// same cell otherwise.
TEST(Jps3d, OrderSwapsCostTheSameAndOtherTurnsCostMore) {
  for (int d = 0; d < 27; ++d)
    for (int e = 0; e < 27; ++e) {
      if (d == 13 || e == 13) continue;
      const int dv[3] = {d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1}, ev[3] = {e % 3 - 1, e / 3 % 3 - 1, e / 9 - 1};
      bool e_in_d = true, d_in_e = true;
      for (int a = 0; a < 3; ++a) {
        e_in_d = e_in_d && (ev[a] == 0 || ev[a] == dv[a]);
        d_in_e = d_in_e && (dv[a] == 0 || dv[a] == ev[a]);
      }
      if (e_in_d) continue;  // canonical: no turn
      const double two = octile_distance(dv[0], dv[1], dv[2]) + octile_distance(ev[0], ev[1], ev[2]);
      const double best = octile_distance(dv[0] + ev[0], dv[1] + ev[1], dv[2] + ev[2]);
      if (d_in_e)
        EXPECT_NEAR(best, two, 1e-12) << d << " " << e;
      else
        EXPECT_LT(best, two - 1e-6) << d << " " << e;
    }
}

}  // namespace
}  // namespace uavplan
