#include "uavplan/planning/registry.h"

#include <functional>
#include <stdexcept>

#include "uavplan/planning/cells/cell_astar.h"
#include "uavplan/planning/cells/cellular_aco.h"
#include "uavplan/planning/field/apf.h"
#include "uavplan/planning/graph/aco_voronoi.h"
#include "uavplan/planning/pso/pso_mpc.h"
#include "uavplan/planning/pso/pso_single.h"
#include "uavplan/planning/sampling/rrt.h"
#include "uavplan/planning/search/astar_planner.h"
#include "uavplan/planning/search/directional_astar.h"

namespace uavplan {
namespace {

struct Entry {
  PlannerInfo info;
  std::function<std::unique_ptr<Planner>(const Params&)> make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
      {{"astar", "grid A* on a voxelised world, 26 neighbours, shortcut and turn shaping"},
       [](const Params& p) { return std::make_unique<AStarPlanner>(AStarOptions::from_params(p)); }},
      {{"directional_astar",
        "P4 directional A*: a cone of M yaw x M pitch directions at step L, turn and climb limits held"},
       [](const Params& p) {
         return std::make_unique<DirectionalAStarPlanner>(DirectionalAStarOptions::from_params(p));
       }},
      {{"cellular_aco", "P2 cellular ant colony on the digital cell map: around or over buildings by the penalty J",
        false},
       [](const Params& p) { return std::make_unique<CellularAcoPlanner>(CellularAcoOptions::from_params(p)); }},
      {{"cell_astar", "A* on P2's cell graph with the same penalty J (optimal for it; the ant colony's baseline)"},
       [](const Params& p) { return std::make_unique<CellAStarPlanner>(CellAStarOptions::from_params(p)); }},
      {{"rrt", "P1's common RRT: goal bias 0.5, fixed step, uniform samples, no pruning (the baseline)", false},
       [](const Params& p) {
         return std::make_unique<RrtPlanner>("rrt", RrtOptions::from_params(p, RrtVariant::common));
       }},
      {{"improved_rrt",
        "P1's improved RRT: chaotic samples, obstacle-velocity growth bias, 5-look-ahead pruning, shortcut", false},
       [](const Params& p) {
         return std::make_unique<RrtPlanner>("improved_rrt", RrtOptions::from_params(p, RrtVariant::improved));
       }},
      {{"aco_voronoi", "P1 ant colony on the threat Voronoi roadmap: tabu lists, tau^alpha eta^beta, Q / L_k deposits",
        false},
       [](const Params& p) {
         return std::make_unique<AcoVoronoiPlanner>(AcoVoronoiOptions::from_params(p, RoadmapSearch::colony),
                                                    RoadmapSearch::colony);
       }},
      {{"voronoi_dijkstra",
        "Dijkstra on P1's threat Voronoi roadmap with the same cost (optimal on it; the colony's baseline)", false},
       [](const Params& p) {
         return std::make_unique<AcoVoronoiPlanner>(AcoVoronoiOptions::from_params(p, RoadmapSearch::dijkstra),
                                                    RoadmapSearch::dijkstra);
       }},
      {{"pso_mpc",
        "P5 multi-step PSO: one waypoint l on per step, (dphi, dh) within the limits, 11-step look-ahead, terminal and "
        "entry-heading terms",
        false, true, false, true},
       [](const Params& p) { return std::make_unique<PsoMpcPlanner>(PsoMpcOptions::from_params(p)); }},
      {{"pso_single",
        "P5's single-step PSO baseline: all waypoints in one swarm, the constraints relaxed into the cost", false, true,
        true},
       [](const Params& p) { return std::make_unique<PsoSinglePlanner>(PsoSingleOptions::from_params(p)); }},
      {{"apf", "P3 improved potential field: capped attraction, sqrt(R)-faded repulsion, 15-degree sector rule", false},
       [](const Params& p) { return std::make_unique<ApfPlanner>(ApfOptions::from_params(p, ApfField::improved)); }},
      {{"apf_traditional", "the traditional potential field (P3's baseline): no cap, no sqrt(R), no sector rule",
        false},
       [](const Params& p) { return std::make_unique<ApfPlanner>(ApfOptions::from_params(p, ApfField::traditional)); }},
  };
  return list;
}

}  // namespace

std::unique_ptr<Planner> make_planner(std::string_view name, const Params& params) {
  for (const Entry& e : entries())
    if (e.info.name == name) return e.make(params);
  std::string known;
  for (const Entry& e : entries()) known += (known.empty() ? "" : ", ") + e.info.name;
  throw std::invalid_argument("unknown planner '" + std::string(name) + "' (known: " + known + ")");
}

bool planner_accepts(std::string_view name, const std::string& key, const std::string& value) {
  try {
    make_planner(name, {{key, value}});
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

std::map<std::string, std::string> planner_parameters(std::string_view name) {
  ParamListing listing;
  make_planner(name, {});
  return listing.defaults;
}

std::vector<PlannerInfo> planner_catalog() {
  std::vector<PlannerInfo> out;
  for (const Entry& e : entries()) out.push_back(e.info);
  return out;
}

}  // namespace uavplan
