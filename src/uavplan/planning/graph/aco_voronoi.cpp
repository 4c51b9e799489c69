#include "uavplan/planning/graph/aco_voronoi.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include "uavplan/core/rng.h"
#include "uavplan/planning/smoothing/turn_limits.h"

namespace uavplan {
namespace {

constexpr double kMinTau = 1e-12;  // evaporation never takes an edge out of the choice entirely

// x^y; the colony's exponents are small whole numbers (alpha 1, beta 1 or 5), where std::pow
// took most of the walk's time.
double raised(double x, double y) {
  if (y == 1.0) return x;
  if (y == std::floor(y) && y >= 0.0 && y <= 8.0) {
    double r = 1.0;
    for (int k = 0; k < static_cast<int>(y); ++k) r *= x;
    return r;
  }
  return std::pow(x, y);
}

// One ant's walk: tabu list by epoch stamps (no clearing per ant), roulette over the edges to
// vertices not yet visited; at a dead end it steps back. False when it is back at the start with
// nowhere to go.
class Walker {
 public:
  explicit Walker(const Roadmap& map) : map_(map), stamp_(map.vertices.size(), 0), weights_(16) {}

  bool walk(std::uint32_t from, std::uint32_t to, const std::vector<double>& tau, const AcoVoronoiOptions& o, Rng& rng,
            std::vector<std::uint32_t>& edges) {
    ++epoch_;
    edges.clear();
    std::uint32_t v = from;
    const Vec3 goal = map_.vertices[to];
    stamp_[v] = epoch_;
    while (v != to) {
      const auto& inc = map_.incident[v];
      const double to_go = o.toward_goal * (1.0 - o.roadmap.k1);
      auto cost_of = [&](std::uint32_t e) {
        return map_.edges[e].cost + to_go * (map_.vertices[map_.other(e, v)] - goal).norm();
      };
      double least = World::kInf;
      for (const std::uint32_t e : inc)
        if (stamp_[map_.other(e, v)] != epoch_) least = std::min(least, cost_of(e));
      if (!std::isfinite(least)) {
        // Every neighbour tabu: step back (this vertex stays tabu), die only back at the start.
        if (edges.empty()) return false;
        v = map_.other(edges.back(), v);
        edges.pop_back();
        continue;
      }
      weights_.assign(inc.size(), 0.0);
      double total = 0.0;
      for (std::size_t k = 0; k < inc.size(); ++k) {
        const std::uint32_t e = inc[k];
        if (stamp_[map_.other(e, v)] == epoch_) continue;
        // eta = 1 / J, taken relative to the cheapest choice so that (J_min / J)^beta stays in range.
        const double eta = least > 0.0 ? least / std::max(cost_of(e), 1e-300) : 1.0;
        weights_[k] = raised(tau[e], o.alpha) * raised(eta, o.beta);
        total += weights_[k];
      }
      double pick = rng.uniform01() * total;
      std::size_t k = 0;
      for (; k + 1 < inc.size(); ++k) {
        if (weights_[k] <= 0.0) continue;
        if (pick < weights_[k]) break;
        pick -= weights_[k];
      }
      while (weights_[k] <= 0.0) --k;  // rounding past the last choice
      edges.push_back(inc[k]);
      v = map_.other(inc[k], v);
      stamp_[v] = epoch_;
    }
    return true;
  }

 private:
  const Roadmap& map_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
  std::vector<double> weights_;
};

GraphRoute route_of(const Roadmap& map, std::uint32_t from, const std::vector<std::uint32_t>& edges) {
  GraphRoute r;
  r.vertices.push_back(from);
  for (const std::uint32_t e : edges) {
    r.vertices.push_back(map.other(e, r.vertices.back()));
    r.cost += map.edges[e].cost;
    r.length_m += map.edges[e].length_m;
  }
  return r;
}

std::uint32_t edge_between(const Roadmap& map, std::uint32_t a, std::uint32_t b) {
  for (const std::uint32_t e : map.incident[a])
    if (map.other(e, a) == b) return e;
  return 0;  // unreachable: consecutive route vertices share an edge
}

}  // namespace

AcoVoronoiOptions AcoVoronoiOptions::read(ParamReader& r, RoadmapSearch search) {
  const bool colony = search == RoadmapSearch::colony;
  AcoVoronoiOptions o;
  o.roadmap.k1 = r.number("k1", o.roadmap.k1, 0.0, 1.0, "P1 eq. 3: the weight of the threat cost against length");
  o.roadmap.threat_prefactor = r.number("threat_prefactor", o.roadmap.threat_prefactor, 0.0, 1e12,
                                        "multiplies J_threat (1: P1's L_i; 1/3: the midpoint rule)");
  o.roadmap.join_nearest = r.integer("join_nearest", o.roadmap.join_nearest, 1, 1000,
                                     "a stop is joined to this many nearest roadmap vertices it sees");
  o.roadmap.outline_spacing_m =
      r.number("outline_spacing_m", o.roadmap.outline_spacing_m, 0.0, 1e9,
               "obstacle outlines sampled this often, m; 0: 1/100 of the bounds' larger side");
  if (colony) {
    o.ants = r.integer("ants", o.ants, 1, 100000, "m, the ants per iteration");
    o.iterations = r.integer("iterations", o.iterations, 1, 100000, "N_max, the colony's iterations");
    o.alpha = r.number("alpha", o.alpha, 0.0, 20.0, "the pheromone's exponent");
    o.beta = r.number("beta", o.beta, 0.0, 20.0, "the heuristic's exponent");
    o.rho = r.number("rho", o.rho, 0.0, 1.0, "the evaporation rate");
    o.q = r.number("q", o.q, 1e-12, 1e12, "Q, the deposit constant");
    const std::string d = r.choice("deposit", o.deposit_by_cost ? "cost" : "length", {"cost", "length"},
                                   "what an ant's deposit divides Q by: cost (J_k) or length (P1's L_k)");
    o.deposit_by_cost = d == "cost";
    o.tau0 = r.number("tau0", o.tau0, 1e-12, 1e12, "the initial pheromone (P1 gives none)");
    o.toward_goal = r.number("toward_goal", o.toward_goal, 0.0, 1.0,
                             "the share of the heuristic that favours edges toward the goal");
    o.elite = r.number("elite", o.elite, 0.0, 1e6, "the best route so far gets elite x Q / L_best more each iteration");
    o.max_min = r.boolean("max_min", o.max_min, "MAX-MIN ant system: only the iteration's best deposits, tau bounded");
  }
  return o;
}

AcoVoronoiOptions AcoVoronoiOptions::from_params(const Params& params, RoadmapSearch search) {
  ParamReader r(params, search == RoadmapSearch::colony ? "aco_voronoi" : "voronoi_dijkstra");
  AcoVoronoiOptions o = read(r, search);
  r.finish();
  return o;
}

std::optional<GraphRoute> aco_route(const Roadmap& map, std::uint32_t from, std::uint32_t to,
                                    const AcoVoronoiOptions& o, std::uint64_t seed, const StopCondition& stop,
                                    PlanStats& stats) {
  if (from == to) return GraphRoute{{from}, 0.0, 0.0};
  std::vector<double> tau(map.edges.size(), o.tau0), deposit(map.edges.size(), 0.0);
  std::optional<GraphRoute> best;
  Walker walker(map);
  std::vector<std::uint32_t> edges;
  const Rng base(seed);
  auto amount = [&](const GraphRoute& r) { return o.q / std::max(o.deposit_by_cost ? r.cost : r.length_m, 1e-300); };
  auto lay = [&](const GraphRoute& r, double d) {
    for (std::size_t k = 1; k < r.vertices.size(); ++k)
      deposit[edge_between(map, r.vertices[k - 1], r.vertices[k])] += d;
  };
  for (int it = 0; it < o.iterations; ++it) {
    if (stop.should_stop(static_cast<std::uint64_t>(it))) return std::nullopt;
    std::fill(deposit.begin(), deposit.end(), 0.0);
    std::optional<GraphRoute> iteration_best;
    for (int ant = 0; ant < o.ants; ++ant) {
      Rng rng = base.split(static_cast<std::uint64_t>(it) * static_cast<std::uint64_t>(o.ants) +
                           static_cast<std::uint64_t>(ant));
      if (!walker.walk(from, to, tau, o, rng, edges)) continue;
      stats.nodes_expanded += edges.size();
      GraphRoute r = route_of(map, from, edges);
      if (!o.max_min) lay(r, amount(r));  // P1 eq. 5-6: every ant deposits
      if (!iteration_best || r.cost < iteration_best->cost) iteration_best = r;
      if (!best || r.cost < best->cost) best = std::move(r);
    }
    if (best && o.elite > 0.0) lay(*best, o.elite * amount(*best));
    if (o.max_min && iteration_best) lay(*iteration_best, amount(*iteration_best));
    double hi = World::kInf, lo = kMinTau;
    if (o.max_min && best) {
      // MAX-MIN ant system (Stuetzle and Hoos 2000): tau in [tau_max / (2 n), 1 / (rho * L_best)].
      hi = amount(*best) / std::max(o.rho, kTinyDivisor);
      lo = hi / (2.0 * static_cast<double>(map.vertices.size()));
      if (it == 0) std::fill(tau.begin(), tau.end(), hi);
    }
    for (std::size_t e = 0; e < tau.size(); ++e) tau[e] = std::clamp((1.0 - o.rho) * tau[e] + deposit[e], lo, hi);
  }
  return best;
}

std::optional<GraphRoute> dijkstra_route(const Roadmap& map, std::uint32_t from, std::uint32_t to, PlanStats& stats) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                      boost::property<boost::edge_weight_t, double>>;
  Graph g(map.vertices.size());
  for (const Roadmap::Edge& e : map.edges) boost::add_edge(e.a, e.b, e.cost, g);
  std::vector<std::size_t> pred(map.vertices.size());
  std::vector<double> dist(map.vertices.size());
  boost::dijkstra_shortest_paths(g, from, boost::predecessor_map(pred.data()).distance_map(dist.data()));
  stats.nodes_expanded += map.vertices.size();
  if (to != from && pred[to] == to) return std::nullopt;
  GraphRoute r;
  for (std::size_t v = to;; v = pred[v]) {
    r.vertices.push_back(static_cast<std::uint32_t>(v));
    if (v == from) break;
  }
  std::reverse(r.vertices.begin(), r.vertices.end());
  r.cost = dist[to];
  for (std::size_t k = 1; k < r.vertices.size(); ++k)
    r.length_m += (map.vertices[r.vertices[k]] - map.vertices[r.vertices[k - 1]]).norm();
  return r;
}

PlanResult AcoVoronoiPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult res;
  const SegmentRule rule(world, pb.uav);
  std::vector<Vec3> stops{pb.uav.start};
  stops.insert(stops.end(), pb.via.begin(), pb.via.end());
  stops.push_back(pb.goal);
  stop.throw_if_stopped();
  Roadmap map = threat_roadmap(world, rule, pb.uav.start.z(), options_.roadmap, stop);
  std::vector<std::uint32_t> at;
  for (const Vec3& s : stops) {
    std::vector<std::uint32_t> also;
    if (!at.empty()) also.push_back(at.back());  // straight on from the previous stop where it sees this one
    at.push_back(join_stop(map, s, rule, world, options_.roadmap, also));
  }
  res.stats.grid_cells = map.vertices.size();
  std::vector<Vec3> wp{stops[0]};
  std::vector<char> pinned{1};
  for (std::size_t leg = 0; leg + 1 < stops.size(); ++leg) {
    if (stop.should_stop()) {
      res.message = "stopped before the route was complete";
      res.reason = Reason::stopped;
      return res;
    }
    if ((stops[leg + 1] - stops[leg]).norm() <= kSamePoint_m) continue;  // a stop repeated: nothing to fly
    const std::optional<GraphRoute> r =
        colony_ ? aco_route(map, at[leg], at[leg + 1], options_, Rng(pb.seed).split(leg).next_u64(), stop, res.stats)
                : dijkstra_route(map, at[leg], at[leg + 1], res.stats);
    if (!r) {
      if (stop.should_stop()) {
        res.message = "stopped before the route was complete";
        res.reason = Reason::stopped;
        return res;
      }
      res.reason = Reason::no_route;
      res.message = leg_name(leg, stops.size()) + ": no route on the threat roadmap (" +
                    std::to_string(map.vertices.size()) + " vertices, " + std::to_string(map.edges.size()) +
                    " edges from " + std::to_string(map.sites) + " sites" +
                    (colony_ ? "; no ant arrived: raise planner.params.iterations or ants, " : "; ") +
                    "a larger planner.params.join_nearest joins the stops to more of it)";
      return res;
    }
    // Heights from this stop's to the next one's, by distance flown (the roadmap is flat).
    const Vec3 a = stops[leg], b = stops[leg + 1];
    double total = 0.0;
    for (std::size_t k = 1; k < r->vertices.size(); ++k)
      total += (map.vertices[r->vertices[k]] - map.vertices[r->vertices[k - 1]]).head<2>().norm();
    double flown = 0.0;
    for (std::size_t k = 1; k < r->vertices.size(); ++k) {
      Vec3 p = map.vertices[r->vertices[k]];
      flown += (p - map.vertices[r->vertices[k - 1]]).head<2>().norm();
      p.z() = k + 1 == r->vertices.size() ? b.z() : a.z() + (total > 0.0 ? flown / total : 1.0) * (b.z() - a.z());
      if (!rule(wp.back(), p)) {
        res.message = leg_name(leg, stops.size()) + ": the route's climb from " + std::to_string(a.z()) + " m to " +
                      std::to_string(b.z()) + " m meets an obstacle or the climb limit near (" + std::to_string(p.x()) +
                      ", " + std::to_string(p.y()) + ")";
        return res;
      }
      if ((p - wp.back()).norm() > 0.0) {
        wp.push_back(p);
        pinned.push_back(k + 1 == r->vertices.size());
      }
    }
  }
  finish_with_turns(wp, pinned, pb.uav, rule, res);
  return res;
}

}  // namespace uavplan
