#include "uavplan/planning/search/best_first.h"

#include <gtest/gtest.h>

#include <queue>

#include "uavplan/core/rng.h"
#include "uavplan/core/vec.h"

namespace uavplan {
namespace {

// A random geometric graph: points in a square, each joined to a few others by edges at least
// as long as the straight line, so the Euclidean distance is a consistent heuristic.
struct Graph {
  struct Edge {
    std::uint32_t to;
    double cost;
  };
  std::vector<Vec3> at;
  std::vector<std::vector<Edge>> out;
};

Graph random_graph(int n, std::uint64_t seed) {
  Rng rng(seed);
  Graph g;
  for (int i = 0; i < n; ++i) g.at.emplace_back(rng.uniform(0, 100), rng.uniform(0, 100), 0.0);
  g.out.resize(n);
  for (int i = 0; i < n; ++i)
    for (int e = 0; e < 3; ++e) {
      const auto j = static_cast<std::uint32_t>(rng.uniform_int(0, n - 1));
      const double c = (g.at[i] - g.at[j]).norm() * rng.uniform(1.0, 1.5);
      g.out[i].push_back({j, c});
      g.out[j].push_back({static_cast<std::uint32_t>(i), c});
    }
  return g;
}

// Oracle: textbook Dijkstra.
std::vector<double> dijkstra(const Graph& g, std::uint32_t s) {
  std::vector<double> d(g.at.size(), std::numeric_limits<double>::infinity());
  using E = std::pair<double, std::uint32_t>;
  std::priority_queue<E, std::vector<E>, std::greater<>> pq;
  d[s] = 0;
  pq.push({0, s});
  while (!pq.empty()) {
    const auto [du, u] = pq.top();
    pq.pop();
    if (du > d[u]) continue;
    for (const Graph::Edge& e : g.out[u])
      if (du + e.cost < d[e.to]) pq.push({d[e.to] = du + e.cost, e.to});
  }
  return d;
}

struct GraphExpansion {
  const Graph& g;
  std::uint64_t stop_at = 0;  // 0: never
  int settled = 0;
  bool stop_now(std::uint64_t expanded) const { return stop_at && expanded >= stop_at; }
  void settle(std::uint32_t) { ++settled; }
  template <class Relax>
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) const {
    for (const Graph::Edge& e : g.out[id]) relax(e.to, n.g + e.cost, id, e.to);
  }
};

// The goal's g is Dijkstra's distance, and the path's edges add up to it, whatever the open
// list's buckets and with or without a heuristic.
TEST(BestFirst, FindsDijkstrasDistanceWithEitherOpenListAndHeuristic) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Graph g = random_graph(400, seed);
    const std::vector<double> d = dijkstra(g, 0);
    for (const double width : {std::numeric_limits<double>::infinity(), 2.0})
      for (const bool euclidean : {false, true}) {
        const auto goal = static_cast<std::uint32_t>(1 + seed * 13 % 399);
        const auto h = [&](std::uint32_t v) { return euclidean ? (g.at[v] - g.at[goal]).norm() : 0.0; };
        BestFirst<> search;
        search.begin(400, h(0), width);
        GraphExpansion expansion{g};
        SearchCounts counts;
        const SearchEnd end = search.run(expansion, h, 0u, SearchBuffers::kNoParent, 0u, goal, counts);
        ASSERT_EQ(end == SearchEnd::goal, std::isfinite(d[goal])) << seed;
        EXPECT_EQ(expansion.settled, static_cast<int>(counts.expanded) + (end == SearchEnd::goal ? 1 : 0));
        if (end != SearchEnd::goal) continue;
        EXPECT_NEAR(search.node(goal).g, d[goal], 1e-9) << seed;
        const std::vector<std::int64_t> path = search.path(0, goal);
        double along = 0.0;
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
          double best = std::numeric_limits<double>::infinity();
          for (const Graph::Edge& e : g.out[path[i]])
            if (e.to == path[i + 1]) best = std::min(best, e.cost);
          along += best;
        }
        EXPECT_NEAR(along, d[goal], 1e-9) << seed;
        EXPECT_GE(counts.generated, counts.expanded);
        EXPECT_GE(counts.open_max, 1u);
        // Opened: every node that has a g, each once (a node again when its g improves is not).
        std::uint64_t with_g = 0;
        for (std::uint32_t v = 0; v < 400; ++v) with_g += std::isfinite(search.node(v).g) ? 1 : 0;
        EXPECT_EQ(counts.opened, with_g) << seed;
        EXPECT_LE(counts.opened, counts.generated + 1) << seed;
      }
  }
}

// The lazy heuristic (refine): children go in with h = 0 and a node's f is raised to the exact
// distance to the goal as it comes off the list. The search closes the nodes that A* with the
// exact heuristic closes, in the same order (same count), and finds the same distance; refine
// is asked only for nodes taken off the list. A node refined to infinity is never expanded.
struct LazyExpansion : GraphExpansion {
  const std::vector<double>& to_goal;
  std::uint32_t walled = SearchBuffers::kNoParent;  // refined to infinity (kNoParent: none)
  int refined = 0;
  double refine(std::uint32_t id, double f, double g_id) {
    ++refined;
    if (id == walled) return std::numeric_limits<double>::infinity();
    return std::max(f, g_id + to_goal[id]);
  }
  void settle(std::uint32_t id) {
    ++settled;
    EXPECT_NE(id, walled);
  }
};

TEST(BestFirst, RefineRaisesFAsNodesComeOffTheList) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Graph g = random_graph(400, seed);
    const auto goal = static_cast<std::uint32_t>(1 + seed * 17 % 399);
    const std::vector<double> from_start = dijkstra(g, 0), to_goal = dijkstra(g, goal);
    if (!std::isfinite(to_goal[0])) continue;
    const auto exact = [&](std::uint32_t v) { return to_goal[v]; };
    const auto zero = [](std::uint32_t) { return 0.0; };
    BestFirst<> eager;
    eager.begin(400, exact(0), 2.0);
    GraphExpansion plain{g};
    SearchCounts eager_counts;
    ASSERT_EQ(eager.run(plain, exact, 0u, SearchBuffers::kNoParent, 0u, goal, eager_counts), SearchEnd::goal);
    BestFirst<> lazy;
    lazy.begin(400, 0.0, 2.0);
    LazyExpansion refining{{g}, to_goal};
    SearchCounts lazy_counts;
    ASSERT_EQ(lazy.run(refining, zero, 0u, SearchBuffers::kNoParent, 0u, goal, lazy_counts), SearchEnd::goal);
    EXPECT_NEAR(lazy.node(goal).g, from_start[goal], 1e-9) << seed;
    EXPECT_EQ(lazy_counts.expanded, eager_counts.expanded) << seed;
    EXPECT_LE(refining.refined, static_cast<int>(2 * lazy_counts.generated + 1));
    // The first node of the optimal path walled off: the route goes around it or none is found.
    const std::vector<std::int64_t> path = lazy.path(0, goal);
    if (path.size() < 3) continue;
    LazyExpansion walling{{g}, to_goal, static_cast<std::uint32_t>(path[1])};
    lazy.begin(400, 0.0, 2.0);
    SearchCounts c;
    const SearchEnd end = lazy.run(walling, zero, 0u, SearchBuffers::kNoParent, 0u, goal, c);
    if (end == SearchEnd::goal) {
      EXPECT_GE(lazy.node(goal).g, from_start[goal] - 1e-9);
    }
  }
}

TEST(BestFirst, EndsWhenThePolicyStopsOrTheListRunsDry) {
  const Graph g = random_graph(400, 3);
  const auto zero = [](std::uint32_t) { return 0.0; };
  BestFirst<> search;
  search.begin(401);
  GraphExpansion stopping{g, 5};
  SearchCounts counts;
  EXPECT_EQ(search.run(stopping, zero, 0u, SearchBuffers::kNoParent, 0u, 400u, counts), SearchEnd::stopped);
  EXPECT_EQ(counts.expanded, 5u);
  // Node 400 has no edges: every reachable node is closed, then the list is dry. A second
  // query on the same buffers starts clean.
  for (int round = 0; round < 2; ++round) {
    search.begin(401);
    GraphExpansion all{g};
    SearchCounts c;
    EXPECT_EQ(search.run(all, zero, 0u, SearchBuffers::kNoParent, 0u, 400u, c), SearchEnd::exhausted);
    const std::vector<double> d = dijkstra(g, 0);
    const auto reachable = std::count_if(d.begin(), d.end(), [](double v) { return std::isfinite(v); });
    EXPECT_EQ(c.expanded, static_cast<std::uint64_t>(reachable));
  }
}

// A policy that writes down the order of its expansions and stops every `every` of them.
struct RecordingExpansion {
  const Graph& g;
  std::vector<std::uint32_t>& order;
  std::uint64_t every = 0;  // 0: never stops
  bool stop_now(std::uint64_t expanded) const { return every != 0 && expanded % every == 0; }
  template <class Relax>
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) const {
    order.push_back(id);
    for (const Graph::Edge& e : g.out[id]) relax(e.to, n.g + e.cost, id, e.to);
  }
};

// A search stopped every few expansions and resumed each time expands what the search run
// through expands, in the same order (the node closed as it stopped is expanded on resuming), and
// counts the same.
TEST(BestFirst, AStoppedSearchResumesWhereItStopped) {
  const Graph g = random_graph(600, 11);
  const auto h = [&](std::uint32_t v) { return (g.at[v] - g.at[599]).norm(); };
  BestFirst<> search;
  search.begin(600);
  std::vector<std::uint32_t> through, sliced;
  RecordingExpansion once{g, through};
  SearchCounts c1;
  ASSERT_EQ(search.run(once, h, 0u, SearchBuffers::kNoParent, 0u, 599u, c1), SearchEnd::goal);
  const double g1 = search.node(599).g;
  ASSERT_GT(through.size(), 20u);

  search.begin(600);
  RecordingExpansion turns{g, sliced, 3};
  SearchCounts c2;
  search.seed(h, 0u, SearchBuffers::kNoParent, 0u, c2);
  int stops = 0;
  SearchEnd end = SearchEnd::stopped;
  while ((end = search.resume(turns, h, 599u, c2)) == SearchEnd::stopped) ++stops;
  EXPECT_EQ(end, SearchEnd::goal);
  EXPECT_GT(stops, 5);
  EXPECT_EQ(sliced, through);
  EXPECT_EQ(c2.expanded, c1.expanded);
  EXPECT_EQ(c2.generated, c1.generated);
  EXPECT_EQ(search.node(599).g, g1);
}

}  // namespace
}  // namespace uavplan
