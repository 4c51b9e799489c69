#include "uavplan/planning/registry.h"

#include <functional>
#include <stdexcept>

#include "uavplan/core/text.h"

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
  // Reads its options from r (their declaration) and builds the planner.
  std::function<std::unique_ptr<Planner>(ParamReader&)> make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
      {{"astar",
        "optimal grid search on a voxelised world (JPS where it applies, else A*), 26 neighbours, shortcut and turn "
        "shaping"},
       [](ParamReader& r) { return std::make_unique<AStarPlanner>(AStarOptions::read(r)); }},
      {{"directional_astar",
        "P4 directional A*: a cone of M yaw x M pitch directions at step L, turn and climb limits held"},
       [](ParamReader& r) { return std::make_unique<DirectionalAStarPlanner>(DirectionalAStarOptions::read(r)); }},
      {{"cellular_aco", "P2 cellular ant colony on the digital cell map: around or over buildings by the penalty J",
        false},
       [](ParamReader& r) { return std::make_unique<CellularAcoPlanner>(CellularAcoOptions::read(r)); }},
      {{"cell_astar", "A* on P2's cell graph with the same penalty J (optimal for it; the ant colony's baseline)"},
       [](ParamReader& r) { return std::make_unique<CellAStarPlanner>(CellAStarOptions::read(r)); }},
      {{"rrt", "P1's common RRT: goal bias 0.5, fixed step, uniform samples, no pruning (the baseline)", false},
       [](ParamReader& r) { return std::make_unique<RrtPlanner>("rrt", RrtOptions::read(r, RrtVariant::common)); }},
      {{"improved_rrt",
        "P1's improved RRT: chaotic samples, obstacle-velocity growth bias, 5-look-ahead pruning, shortcut", false},
       [](ParamReader& r) {
         return std::make_unique<RrtPlanner>("improved_rrt", RrtOptions::read(r, RrtVariant::improved));
       }},
      {{"aco_voronoi", "P1 ant colony on the threat Voronoi roadmap: tabu lists, tau^alpha eta^beta, Q / L_k deposits",
        false},
       [](ParamReader& r) {
         return std::make_unique<AcoVoronoiPlanner>(AcoVoronoiOptions::read(r, RoadmapSearch::colony),
                                                    RoadmapSearch::colony);
       }},
      {{"voronoi_dijkstra",
        "Dijkstra on P1's threat Voronoi roadmap with the same cost (optimal on it; the colony's baseline)", false},
       [](ParamReader& r) {
         return std::make_unique<AcoVoronoiPlanner>(AcoVoronoiOptions::read(r, RoadmapSearch::dijkstra),
                                                    RoadmapSearch::dijkstra);
       }},
      {{"pso_mpc",
        "P5 multi-step PSO: one waypoint l on per step, (dphi, dh) within the limits, 11-step look-ahead, terminal and "
        "entry-heading terms",
        false, true, false, true},
       [](ParamReader& r) { return std::make_unique<PsoMpcPlanner>(PsoMpcOptions::read(r)); }},
      {{"pso_single",
        "P5's single-step PSO baseline: all waypoints in one swarm, the constraints relaxed into the cost", false, true,
        true},
       [](ParamReader& r) { return std::make_unique<PsoSinglePlanner>(PsoSingleOptions::read(r)); }},
      {{"apf", "P3 improved potential field: capped attraction, sqrt(R)-faded repulsion, 15-degree sector rule", false},
       [](ParamReader& r) { return std::make_unique<ApfPlanner>(ApfOptions::read(r, ApfField::improved)); }},
      {{"apf_traditional", "the traditional potential field (P3's baseline): no cap, no sqrt(R), no sector rule",
        false},
       [](ParamReader& r) { return std::make_unique<ApfPlanner>(ApfOptions::read(r, ApfField::traditional)); }},
  };
  return list;
}

const Entry* find_entry(std::string_view name) {
  for (const Entry& e : entries())
    if (e.info.name == name) return &e;
  return nullptr;
}

const Entry& entry(std::string_view name) {
  if (const Entry* e = find_entry(name)) return *e;
  std::string known;
  for (const Entry& e : entries()) known += (known.empty() ? "" : ", ") + e.info.name;
  throw std::invalid_argument("unknown planner '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace

std::unique_ptr<Planner> make_planner(std::string_view name, const Params& params) {
  const Entry& e = entry(name);
  ParamReader r(params, e.info.name);
  std::unique_ptr<Planner> planner = e.make(r);
  r.finish();
  return planner;
}

bool planner_accepts(std::string_view name, const std::string& key, const std::string& value) {
  const Entry* e = find_entry(name);
  if (!e) return false;
  const Params one{{key, value}};
  ParamReader r(one, e->info.name, ParamReader::Mode::collect);
  e->make(r);
  r.finish();
  return r.problems().empty();
}

std::vector<ParamDecl> planner_parameters(std::string_view name) {
  const Entry& e = entry(name);
  const Params none;
  ParamReader r(none, e.info.name, ParamReader::Mode::collect);
  e.make(r);
  return r.declarations();
}

std::vector<PlannerInfo> planner_catalog() {
  std::vector<PlannerInfo> out;
  for (const Entry& e : entries()) out.push_back(e.info);
  return out;
}

std::string planner_catalog_text(bool markdown) {
  std::string out;
  for (const Entry& e : entries()) {
    const std::vector<ParamDecl> params = planner_parameters(e.info.name);
    if (markdown)
      out += "\n**`" + e.info.name + "`**: " + e.info.description +
             ".\n\n| parameter | type | range | default | meaning |\n" + "|---|---|---|---|---|\n";
    else
      out += e.info.name + ": " + e.info.description + "\n";
    for (const ParamDecl& d : params) {
      std::string range;
      if (d.kind == ParamKind::number || d.kind == ParamKind::integer)
        range = "[" + num_text(d.lo) + ", " + num_text(d.hi) + "]";
      for (std::size_t i = 0; i < d.choices.size() && d.kind == ParamKind::choice; ++i)
        range += (i ? " | " : "") + d.choices[i];
      if (markdown)
        out += "| `" + d.key + "` | " + std::string(to_string(d.kind)) + " | " + (range.empty() ? "-" : range) + " | " +
               d.default_value + " | " + d.doc + " |\n";
      else
        out += "    " + d.key + " (" + std::string(to_string(d.kind)) + (range.empty() ? "" : " " + range) + "; " +
               d.default_value + "): " + d.doc + "\n";
    }
  }
  return out;
}

}  // namespace uavplan
