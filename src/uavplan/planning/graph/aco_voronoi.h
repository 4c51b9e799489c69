// P1's global layer: an ant colony on the threat Voronoi roadmap (threat_roadmap.h). Ants start
// at the start, keep a tabu list of the vertices they visited, step along an edge with
// P ~ tau^alpha eta^beta (eta = 1 / J of the edge), and die where every neighbour is tabu.
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

struct AcoVoronoiOptions {
  RoadmapOptions roadmap;
  int ants = 10;              // m
  int iterations = 100;       // N_max
  double alpha = 1.0;
  double beta = 5.0;
  double rho = 0.2;
  double q = 1.0;
  bool deposit_by_cost = false;  // Q / J_k instead of P1's Q / L_k
  // The colony's keys, and the roadmap's (k1, threat_prefactor, join_nearest) that both read.
  static AcoVoronoiOptions from_params(const Params& params, bool colony = true);
};

struct GraphRoute {
  std::vector<std::uint32_t> vertices;
  double cost = 0.0, length_m = 0.0;
};

// The colony's best route from `from` to `to`; nothing when no ant arrived.
std::optional<GraphRoute> aco_route(const Roadmap& map, std::uint32_t from, std::uint32_t to, const AcoVoronoiOptions& o,
                                    std::uint64_t seed, const StopCondition& stop, PlanStats& stats);
// The least-cost route (Dijkstra); nothing when `to` is not connected to `from`.
std::optional<GraphRoute> dijkstra_route(const Roadmap& map, std::uint32_t from, std::uint32_t to, PlanStats& stats);

class AcoVoronoiPlanner final : public Planner {
 public:
  AcoVoronoiPlanner(AcoVoronoiOptions options, bool colony) : options_(options), colony_(colony) {}
  std::string_view name() const override { return colony_ ? "aco_voronoi" : "voronoi_dijkstra"; }

 private:
  PlanResult do_plan(const Problem& problem, const World& world, const StopCondition& stop) const override;
  AcoVoronoiOptions options_;
  bool colony_;
};

}  // namespace uavplan
