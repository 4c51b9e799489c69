// P1's global layer: an ant colony on the threat Voronoi roadmap (threat_roadmap.h). Ants start
// at the start, keep a tabu list of the vertices they visited, step along an edge with
// P ~ tau^alpha eta^beta (eq. 4; eta below), and step back from a dead end (P1 does not say).
// After each of N_max iterations tau evaporates by rho and each arrived ant deposits Q / L_k on
// its edges (P1's literal rule; Q / J_k as an option). The best route by cost J is kept.
// Its baseline, `voronoi_dijkstra`: Dijkstra (Boost.Graph) on the same roadmap and cost, the
// optimum the colony is measured against.
// The roadmap is 2-D at the start's height; heights along the route go linearly from the
// start's to the goal's by distance flown, and every segment is checked.
#pragma once

#include <optional>

#include "uavplan/planning/graph/threat_roadmap.h"
#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"

namespace uavplan {

// How a route is searched on the roadmap: P1's ant colony, or Dijkstra (its baseline).
enum class RoadmapSearch { colony, dijkstra };

struct AcoVoronoiOptions {
  RoadmapOptions roadmap;
  int ants = 10;         // m
  int iterations = 100;  // N_max
  double alpha = 1.0;
  // P1 gives beta 5 and Q / L_k. With the goal term in eta (below) and threats that dominate the
  // cost, beta 5 makes each step all but greedy and Q / L_k rewards short routes, not cheap ones:
  // bench p1 measures 1.77x the optimum on 1e6-weight fields against 1.04x with beta 1 and
  // Q / J_k, the defaults (docs/decisions/0007). `beta: 5, deposit: length` is P1's setting.
  double beta = 1.0;
  double rho = 0.2;
  double q = 1.0;
  bool deposit_by_cost = true;  // Q / J_k; false: P1's Q / L_k
  double tau0 = 1.0;            // initial pheromone (P1 gives none)
  // eta = 1 / (J_edge + toward_goal * (1 - k1) * |next - goal|): 0 is P1's 1 / J; 1 (default)
  // adds a lower bound of the cost still to go, so an ant heads for the goal as A* does. With
  // P1's 1 / J alone ants wander a roadmap of hundreds of vertices (bench p1 shows both).
  double toward_goal = 1.0;
  bool max_min = false;  // MAX-MIN ant system: only the iteration's best deposits, tau bounded
  double elite = 0.0;    // the best route so far gets elite * Q / L_best more each iteration
  // The colony's keys (for the colony), and the roadmap's (k1, threat_prefactor, join_nearest)
  // that both read.
  static AcoVoronoiOptions from_params(const Params& params, RoadmapSearch search = RoadmapSearch::colony);
  // The declaration of its parameters: reads them from r (params.h).
  static AcoVoronoiOptions read(ParamReader& r, RoadmapSearch search = RoadmapSearch::colony);
};

struct GraphRoute {
  std::vector<std::uint32_t> vertices;
  double cost = 0.0, length_m = 0.0;
};

// The colony's best route from `from` to `to`; nothing when no ant arrived.
std::optional<GraphRoute> aco_route(const Roadmap& map, std::uint32_t from, std::uint32_t to,
                                    const AcoVoronoiOptions& o, std::uint64_t seed, const StopCondition& stop,
                                    PlanStats& stats);
// The least-cost route (Dijkstra); nothing when `to` is not connected to `from`.
std::optional<GraphRoute> dijkstra_route(const Roadmap& map, std::uint32_t from, std::uint32_t to, PlanStats& stats);

class AcoVoronoiPlanner final : public Planner {
 public:
  AcoVoronoiPlanner(AcoVoronoiOptions options, RoadmapSearch search)
      : options_(options), colony_(search == RoadmapSearch::colony) {}
  std::string_view name() const override { return colony_ ? "aco_voronoi" : "voronoi_dijkstra"; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  AcoVoronoiOptions options_;
  bool colony_;
};

}  // namespace uavplan
