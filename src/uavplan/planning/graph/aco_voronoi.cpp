#include "uavplan/planning/graph/aco_voronoi.h"

#include <algorithm>
#include <cmath>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include "uavplan/core/rng.h"
#include "uavplan/planning/smoothing/turn_limits.h"

namespace uavplan {
namespace {

constexpr double kMinTau = 1e-12;  // evaporation never takes an edge out of the choice entirely

AcoVoronoiOptions read_options(const Params& params, bool colony) {
  ParamReader r(params, colony ? "aco_voronoi" : "voronoi_dijkstra");
  AcoVoronoiOptions o;
  o.roadmap.k1 = r.number("k1", o.roadmap.k1, 0.0, 1.0);
  o.roadmap.threat_prefactor = r.number("threat_prefactor", o.roadmap.threat_prefactor, 0.0, 1e12);
  o.roadmap.join_nearest = r.integer("join_nearest", o.roadmap.join_nearest, 1, 1000);
  if (colony) {
    o.ants = r.integer("ants", o.ants, 1, 100000);
    o.iterations = r.integer("iterations", o.iterations, 1, 100000);
    o.alpha = r.number("alpha", o.alpha, 0.0, 20.0);
    o.beta = r.number("beta", o.beta, 0.0, 20.0);
    o.rho = r.number("rho", o.rho, 0.0, 1.0);
    o.q = r.number("q", o.q, 1e-12, 1e12);
    const std::string d = r.text("deposit", "length");
    if (d != "length" && d != "cost")
      throw std::invalid_argument("planner.params.deposit: expected 'length' (P1's Q / L_k) or 'cost' (Q / J_k), got '" + d + "'");
    o.deposit_by_cost = d == "cost";
  }
  r.finish();
  return o;
}

// One ant's walk: tabu list by epoch stamps (no clearing per ant), roulette over the edges to
// vertices not yet visited. False when it dies (every neighbour tabu) or wanders past every vertex.
class Walker {
 public:
  explicit Walker(const Roadmap& map) : map_(map), stamp_(map.vertices.size(), 0), weights_(16) {}

  bool walk(std::uint32_t from, std::uint32_t to, const std::vector<double>& tau, const AcoVoronoiOptions& o, Rng& rng,
            std::vector<std::uint32_t>& edges) {
    ++epoch_;
    edges.clear();
    std::uint32_t v = from;
    stamp_[v] = epoch_;
    while (v != to) {
      const auto& inc = map_.incident[v];
      double least = World::kInf;
      for (const std::uint32_t e : inc)
        if (stamp_[map_.other(e, v)] != epoch_) least = std::min(least, map_.edges[e].cost);
      if (!std::isfinite(least)) return false;
      weights_.assign(inc.size(), 0.0);
      double total = 0.0;
      for (std::size_t k = 0; k < inc.size(); ++k) {
        const std::uint32_t e = inc[k];
        if (stamp_[map_.other(e, v)] == epoch_) continue;
        // eta = 1 / J, taken relative to the cheapest choice so that (J_min / J)^beta stays in range.
        const double eta = least > 0.0 ? least / std::max(map_.edges[e].cost, 1e-300) : 1.0;
        weights_[k] = std::pow(tau[e], o.alpha) * std::pow(eta, o.beta);
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

}  // namespace

AcoVoronoiOptions AcoVoronoiOptions::from_params(const Params& params, bool colony) { return read_options(params, colony); }

std::optional<GraphRoute> aco_route(const Roadmap& map, std::uint32_t from, std::uint32_t to, const AcoVoronoiOptions& o,
                                    std::uint64_t seed, const StopCondition& stop, PlanStats& stats) {
  if (from == to) return GraphRoute{{from}, 0.0, 0.0};
  std::vector<double> tau(map.edges.size(), 1.0), deposit(map.edges.size(), 0.0);
  std::optional<GraphRoute> best;
  Walker walker(map);
  std::vector<std::uint32_t> edges;
  const Rng base(seed);
  for (int it = 0; it < o.iterations; ++it) {
    if (stop.should_stop(static_cast<std::uint64_t>(it))) return std::nullopt;
    std::fill(deposit.begin(), deposit.end(), 0.0);
    for (int ant = 0; ant < o.ants; ++ant) {
      Rng rng = base.split(static_cast<std::uint64_t>(it) * static_cast<std::uint64_t>(o.ants) + static_cast<std::uint64_t>(ant));
      if (!walker.walk(from, to, tau, o, rng, edges)) continue;
      stats.nodes_expanded += edges.size();
      GraphRoute r = route_of(map, from, edges);
      const double d = o.q / std::max(o.deposit_by_cost ? r.cost : r.length_m, 1e-300);
      for (const std::uint32_t e : edges) deposit[e] += d;
      if (!best || r.cost < best->cost) best = std::move(r);
    }
    for (std::size_t e = 0; e < tau.size(); ++e) tau[e] = std::max(kMinTau, (1.0 - o.rho) * tau[e] + deposit[e]);
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
  for (std::size_t k = 1; k < r.vertices.size(); ++k) r.length_m += (map.vertices[r.vertices[k]] - map.vertices[r.vertices[k - 1]]).norm();
  return r;
}

PlanResult AcoVoronoiPlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult res;
  const SegmentRule rule(world, pb.uav);
  std::vector<Vec3> stops{pb.uav.start};
  stops.insert(stops.end(), pb.via.begin(), pb.via.end());
  stops.push_back(pb.goal);
  Roadmap map = threat_roadmap(world, rule, pb.uav.start.z(), options_.roadmap);
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
      return res;
    }
    const std::optional<GraphRoute> r =
        colony_ ? aco_route(map, at[leg], at[leg + 1], options_, Rng(pb.seed).split(leg).next_u64(), stop, res.stats)
                : dijkstra_route(map, at[leg], at[leg + 1], res.stats);
    if (!r) {
      if (stop.should_stop()) {
        res.message = "stopped before the route was complete";
        return res;
      }
      res.message = leg_name(leg, stops.size()) + ": no route on the threat roadmap (" + std::to_string(map.vertices.size()) +
                    " vertices, " + std::to_string(map.edges.size()) + " edges from " + std::to_string(map.sites) + " sites" +
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
                      std::to_string(b.z()) + " m meets an obstacle or the climb limit near (" + std::to_string(p.x()) + ", " +
                      std::to_string(p.y()) + ")";
        return res;
      }
      if ((p - wp.back()).norm() > 0.0) {
        wp.push_back(p);
        pinned.push_back(k + 1 == r->vertices.size());
      }
    }
  }
  if (pb.uav.max_turn_rad < kPi - 1e-9 || pb.uav.heading_rad) {
    const TurnShaping shaped =
        enforce_turn_limits(wp, pinned, pb.uav.heading_rad, {pb.uav.max_turn_rad, pb.uav.max_climb_rad}, rule);
    if (!shaped.ok) {
      res.message = "turn limits: " + shaped.message;
      return res;
    }
    wp = shaped.waypoints;
  }
  res.route.waypoints = std::move(wp);
  res.status = Status::solved;
  return res;
}

}  // namespace uavplan
