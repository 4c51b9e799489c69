#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "uavplan/coordination/spacetime/mapf.h"
#include "uavplan/coordination/spacetime/mapf_conflicts.h"
#include "uavplan/coordination/spacetime/safe_interval_astar.h"
#include "uavplan/coordination/spacetime/space_time_astar.h"

namespace uavplan {
namespace {

// A grid from rows of text ('#' blocked), row 0 at y = 0.
struct Grid {
  int width = 0, height = 0;
  std::vector<char> blocked;
  SpaceTimeGraph graph;
  int at(int x, int y) const { return y * width + x; }
};
Grid grid(const std::vector<std::string>& rows) {
  Grid g;
  g.height = static_cast<int>(rows.size());
  g.width = static_cast<int>(rows[0].size());
  for (const std::string& r : rows)
    for (const char c : r) g.blocked.push_back(c == '#');
  g.graph = grid4(g.width, g.height, g.blocked);
  return g;
}

// Conflicts by brute force, pair by pair and step by step: the yardstick of the scan.
bool any_conflict_brute(const std::vector<SpaceTimePath>& paths) {
  std::size_t end = 0;
  for (const SpaceTimePath& p : paths) end = std::max(end, p.size());
  for (std::size_t a = 0; a < paths.size(); ++a)
    for (std::size_t b = a + 1; b < paths.size(); ++b)
      for (int t = 0; t < static_cast<int>(end); ++t) {
        if (vertex_at(paths[a], t) == vertex_at(paths[b], t)) return true;
        if (vertex_at(paths[a], t) == vertex_at(paths[b], t + 1) &&
            vertex_at(paths[b], t) == vertex_at(paths[a], t + 1) &&
            vertex_at(paths[a], t) != vertex_at(paths[a], t + 1))
          return true;
      }
  return false;
}

// A corridor of five cells with one niche under its middle: two agents that swap ends.
MapfProblem corridor_swap() {
  const Grid g = grid({".....", "##.##"});
  return {g.graph, {g.at(0, 0), g.at(4, 0)}, {g.at(4, 0), g.at(0, 0)}};
}

// Safe intervals find the time-expanded search's shortest path under random tables (vertices at
// times, moves, waits, agents staying for ever), and every path they give keeps off the tables.
TEST(SafeIntervalSearch, AsShortAsTheTimeExpandedSearchAndKeepsOff) {
  std::mt19937 rng(21);
  SpaceTimeSearch expanded;
  SafeIntervalSearch intervals;
  SpaceTimeTable table;
  int found = 0;
  for (int k = 0; k < 400; ++k) {
    std::vector<std::string> rows;
    for (int y = 0; y < 9; ++y) {
      std::string r;
      for (int x = 0; x < 9; ++x) r += rng() % 10 < 2 ? '#' : '.';
      rows.push_back(r);
    }
    const Grid g = grid(rows);
    std::vector<int> open;
    for (int v = 0; v < g.graph.vertex_count; ++v)
      if (!g.blocked[v]) open.push_back(v);
    if (open.size() < 4) continue;
    const auto any = [&] { return open[rng() % open.size()]; };
    const int s = any(), t = any();
    table.clear(g.graph.vertex_count);
    for (int e = 0; e < 40; ++e) {
      const int v = any(), time = static_cast<int>(rng() % 20);
      switch (rng() % 5) {
        case 0:
          table.add_stay(v, 10 + time);
          break;
        case 1:
          table.add_move(v, v, time);  // no waiting there then
          break;
        case 2:
          if (g.graph.degree(v) > 0) table.add_move(v, g.graph.next[g.graph.first[v]], time);
          break;
        default:
          table.add_vertex(v, time);
      }
    }
    const std::vector<int> h = distances_to(g.graph, t);
    const SpaceTimeQuery q{s, t, &h, &table, nullptr, 1.0};
    const SpaceTimeAnswer a = expanded.find(g.graph, q, StopCondition{});
    const SpaceTimeAnswer b = intervals.find(g.graph, q, StopCondition{});
    ASSERT_EQ(a.found, b.found) << k;
    if (!b.found) continue;
    ++found;
    ASSERT_EQ(a.cost, b.cost) << k;
    ASSERT_EQ(b.path.front(), s);
    ASSERT_EQ(b.path.back(), t);
    for (int time = 0; time + 1 < static_cast<int>(b.path.size()); ++time) {
      const int u = b.path[time], v = b.path[time + 1];
      ASSERT_TRUE(u == v || g.graph.adjacent(u, v)) << k;
      ASSERT_EQ(table.at(v, time + 1), 0) << k;
      ASSERT_EQ(table.moves(u, v, time), 0) << k;
    }
    ASSERT_LT(table.last_time_at(t), static_cast<int>(b.path.size())) << k;  // it may stay at its goal
  }
  EXPECT_GT(found, 150);
}

TEST(SpaceTimeSearch, AloneItTakesTheShortestPath) {
  const Grid g = grid({"....", ".##.", "...."});
  const std::vector<int> h = distances_to(g.graph, g.at(3, 2));
  SpaceTimeTable none;
  none.clear(g.graph.vertex_count);
  SpaceTimeSearch s;
  const SpaceTimeAnswer a = s.find(g.graph, {g.at(0, 0), g.at(3, 2), &h, &none, nullptr, 1.0}, StopCondition());
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.cost, 5);
  EXPECT_EQ(a.lower_bound, 5);
  EXPECT_FALSE(mapf_solution_problem(g.graph, {g.at(0, 0)}, {g.at(3, 2)}, {a.path}).has_value());
}

TEST(SpaceTimeSearch, KeepsOffForbiddenVerticesMovesAndAGoalTakenLater) {
  const Grid g = grid({"...."});
  const std::vector<int> h = distances_to(g.graph, g.at(3, 0));
  SpaceTimeTable forbidden;
  forbidden.clear(g.graph.vertex_count);
  forbidden.add_vertex(g.at(2, 0), 2);            // it must wait once on the way
  forbidden.add_move(g.at(0, 0), g.at(1, 0), 0);  // and cannot leave at once
  forbidden.add_vertex(g.at(3, 0), 7);            // the goal is taken at t = 7: it ends after
  SpaceTimeSearch s;
  const SpaceTimeAnswer a = s.find(g.graph, {g.at(0, 0), g.at(3, 0), &h, &forbidden, nullptr, 1.0}, StopCondition());
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.cost, 8);
  EXPECT_EQ(a.path[1], g.at(0, 0));
  for (std::size_t t = 0; t < a.path.size(); ++t) {
    EXPECT_FALSE(a.path[t] == g.at(2, 0) && t == 2);
    EXPECT_FALSE(a.path[t] == g.at(3, 0) && t == 7);
  }
}

TEST(SpaceTimeSearch, AGoalSomeoneStaysAtForEverIsNeverReached) {
  const Grid g = grid({"...."});
  const std::vector<int> h = distances_to(g.graph, g.at(3, 0));
  SpaceTimeTable forbidden;
  forbidden.clear(g.graph.vertex_count);
  forbidden.add_stay(g.at(2, 0), 5);  // the only way is shut from t = 5 on
  SpaceTimeSearch s;
  SpaceTimeAnswer a = s.find(g.graph, {g.at(0, 0), g.at(3, 0), &h, &forbidden, nullptr, 1.0}, StopCondition());
  EXPECT_TRUE(a.found);  // it passes before
  forbidden.clear(g.graph.vertex_count);
  forbidden.add_stay(g.at(2, 0), 1);
  a = s.find(g.graph, {g.at(0, 0), g.at(3, 0), &h, &forbidden, nullptr, 1.0}, StopCondition());
  EXPECT_FALSE(a.found);
  EXPECT_LT(a.expanded, 100u);  // one sweep of the still graph, not a search through time
}

TEST(MapfConflicts, FindsTheFirstMeetingAndSwap) {
  // a: 0 1 2, b: 2 1 0 on a line -> they meet at 1 at t = 1.
  const std::vector<SpaceTimePath> meet = {{0, 1, 2}, {2, 1, 0}};
  const auto c = first_conflict(meet, 3);
  ASSERT_TRUE(c.has_value());
  EXPECT_FALSE(c->swap());
  EXPECT_EQ(c->t, 1);
  EXPECT_EQ(c->v, 1);
  // a: 0 1, b: 1 0 -> they swap in step 0.
  const std::vector<SpaceTimePath> swap = {{0, 1}, {1, 0}};
  const auto s = first_conflict(swap, 2);
  ASSERT_TRUE(s.has_value());
  EXPECT_TRUE(s->swap());
  EXPECT_EQ(s->t, 0);
  // An agent that stays at its goal is met there later.
  const std::vector<SpaceTimePath> parked = {{1}, {3, 2, 1, 0}};
  const auto p = first_conflict(parked, 4);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->t, 2);
  // Three at one vertex: the second and the third each meet the first.
  EXPECT_EQ(count_conflicts({{0, 1, 2}, {2, 1, 0}, {1, 1, 1}}, 3), 2);
}

TEST(MapfConflicts, TheScanFindsWhatBruteForceFinds) {
  std::mt19937 rng(3);
  const Grid g = grid({"....", "....", "...."});
  int with = 0;
  for (int k = 0; k < 2000; ++k) {
    std::vector<SpaceTimePath> paths(3);
    for (SpaceTimePath& p : paths) {  // random walks with waits
      p.push_back(std::uniform_int_distribution<int>(0, 11)(rng));
      const int steps = std::uniform_int_distribution<int>(0, 6)(rng);
      for (int s = 0; s < steps; ++s) {
        const int u = p.back(), d = g.graph.degree(u);
        const int pick = std::uniform_int_distribution<int>(0, d)(rng);
        p.push_back(pick == d ? u : g.graph.next[g.graph.first[u] + pick]);
      }
    }
    const bool brute = any_conflict_brute(paths);
    with += brute;
    ASSERT_EQ(first_conflict(paths, g.graph.vertex_count).has_value(), brute) << k;
    ASSERT_EQ(count_conflicts(paths, g.graph.vertex_count) > 0, brute) << k;
  }
  EXPECT_GT(with, 200);
  EXPECT_LT(with, 1800);
}

TEST(MapfConflicts, TheCheckRejectsEveryKindOfWrongSolution) {
  const Grid g = grid({"...", ".#."});
  const std::vector<int> starts = {g.at(0, 0), g.at(2, 0)}, goals = {g.at(2, 0), g.at(0, 0)};
  EXPECT_TRUE(mapf_solution_problem(g.graph, starts, goals, {{0, 1, 2}, {2, 1, 0}}).has_value());     // meet
  EXPECT_TRUE(mapf_solution_problem(g.graph, starts, goals, {{0, 2}, {2, 5, 4, 3, 0}}).has_value());  // jump
  EXPECT_TRUE(mapf_solution_problem(g.graph, starts, goals, {{0, 1}, {2, 5, 4, 3, 0}}).has_value());  // not at goal
  EXPECT_TRUE(mapf_solution_problem(g.graph, starts, goals, {{0, 1, 2}}).has_value());                // one path
  // Around through the lower row: a 0 1 2, b 2 5 ... cannot pass (4 blocked): b waits at 5? 5 -> 4 is blocked.
  const Grid open = grid({"...", "..."});
  EXPECT_FALSE(mapf_solution_problem(open.graph, {0, 2}, {2, 0}, {{0, 1, 2}, {2, 5, 4, 3, 0}}).has_value());
}

class EveryMethod : public ::testing::TestWithParam<MapfMethod> {};
using CompleteMethod = EveryMethod;

TEST_P(CompleteMethod, SwapsTwoAgentsThroughACorridorWithOneNiche) {
  const MapfProblem p = corridor_swap();
  MapfOptions o;
  o.method = GetParam();
  const MapfResult r = solve_mapf(p, o);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_FALSE(mapf_solution_problem(p.graph, p.starts, p.goals, r.paths).has_value());
  // One steps into the niche and out again (2) and the other waits once: 4 + 4 + 3.
  if (GetParam() == MapfMethod::cbs) {
    EXPECT_EQ(r.sum_of_costs, 11);
  }
  EXPECT_LE(r.sum_of_costs, static_cast<int>(1.3 * 11));
}

// Prioritised planning is incomplete: whoever goes first takes the corridor at once, and the
// other cannot reach the niche in time, in either order.
TEST(Prioritized, CannotYieldInACorridor) {
  MapfOptions o;
  o.method = MapfMethod::prioritized;
  const MapfResult r = solve_mapf(corridor_swap(), o);
  EXPECT_FALSE(r.solved());
  EXPECT_EQ(r.reason, Reason::conflict);
  EXPECT_NE(r.message.find("no order"), std::string::npos);
}

TEST_P(EveryMethod, ACorridorWithoutANicheHasNoSolution) {
  const Grid g = grid({"....."});
  const MapfProblem p{g.graph, {g.at(0, 0), g.at(4, 0)}, {g.at(4, 0), g.at(0, 0)}};
  MapfOptions o;
  o.method = GetParam();
  o.stop = StopCondition::time_limit(0.2);  // a conflict-based search cannot prove it: it stops
  const MapfResult r = solve_mapf(p, o);
  EXPECT_FALSE(r.solved());
  EXPECT_FALSE(r.message.empty());
}

INSTANTIATE_TEST_SUITE_P(Mapf, CompleteMethod,
                         ::testing::Values(MapfMethod::automatic, MapfMethod::ecbs, MapfMethod::cbs));
INSTANTIATE_TEST_SUITE_P(Mapf, EveryMethod,
                         ::testing::Values(MapfMethod::automatic, MapfMethod::prioritized, MapfMethod::ecbs,
                                           MapfMethod::cbs));

// Random 8 x 8 worlds with 5 agents: every method's solution holds, CBS's sum of costs is the
// least of all (it is optimal), ECBS's within w of it, and no sum is below the lone paths'.
TEST(Mapf, CbsIsTheLeastAndEcbsWithinItsBoundOnRandomWorlds) {
  std::mt19937 rng(5);
  int compared = 0;
  for (int world = 0; world < 40; ++world) {
    std::vector<char> blocked(64, 0);
    for (char& b : blocked) b = std::uniform_int_distribution<int>(0, 99)(rng) < 20;
    std::vector<int> free;
    for (int v = 0; v < 64; ++v)
      if (!blocked[v]) free.push_back(v);
    std::shuffle(free.begin(), free.end(), rng);
    MapfProblem p{grid4(8, 8, blocked),
                  {free[0], free[1], free[2], free[3], free[4]},
                  {free[5], free[6], free[7], free[8], free[9]}};
    MapfOptions o;
    o.stop = StopCondition::time_limit(5.0);
    o.method = MapfMethod::cbs;
    const MapfResult best = solve_mapf(p, o);
    if (!best.solved()) continue;  // walled-off goals
    ++compared;
    EXPECT_FALSE(any_conflict_brute(best.paths));
    EXPECT_GE(best.sum_of_costs, best.lower_bound);
    for (const MapfMethod m : {MapfMethod::ecbs, MapfMethod::prioritized, MapfMethod::automatic}) {
      o.method = m;
      const MapfResult r = solve_mapf(p, o);
      if (!r.solved()) continue;
      EXPECT_FALSE(mapf_solution_problem(p.graph, p.starts, p.goals, r.paths).has_value()) << to_string(m);
      EXPECT_FALSE(any_conflict_brute(r.paths)) << to_string(m);
      EXPECT_GE(r.sum_of_costs, best.sum_of_costs) << to_string(m) << " world " << world;
      if (m != MapfMethod::prioritized) {
        EXPECT_LE(r.sum_of_costs, 1.3 * best.sum_of_costs) << to_string(m);
      }
    }
  }
  EXPECT_GE(compared, 20);
}

TEST(Mapf, MistakenProblemsAreRefused) {
  const MapfProblem swap = corridor_swap();
  MapfProblem shared_goal = swap;
  shared_goal.goals[1] = shared_goal.goals[0];
  EXPECT_THROW(solve_mapf(shared_goal, {}), std::invalid_argument);
  MapfProblem off = swap;
  off.starts[0] = 99;
  EXPECT_THROW(solve_mapf(off, {}), std::invalid_argument);
  MapfProblem huge;  // 300 agents on 2^20 cells: 1.2 GB of distance tables
  huge.graph.vertex_count = 1 << 20;
  for (int i = 0; i < 300; ++i) {
    huge.starts.push_back(i);
    huge.goals.push_back(1000 + i);
  }
  EXPECT_NE(mapf_problem_mistake(huge).find("MiB of distance tables"), std::string::npos);
  huge.starts.resize(200);
  huge.goals.resize(200);
  EXPECT_EQ(mapf_problem_mistake(huge), "");
  MapfOptions bad_w;
  bad_w.w = 0.5;
  EXPECT_THROW(solve_mapf(swap, bad_w), std::invalid_argument);
}

TEST(Mapf, SameAnswerEveryTime) {
  const MapfProblem p = corridor_swap();
  MapfOptions o;
  o.method = MapfMethod::ecbs;
  EXPECT_EQ(solve_mapf(p, o).paths, solve_mapf(p, o).paths);
}

}  // namespace
}  // namespace uavplan
