// uavplan info SCENARIO: a summary of a scenario's world, UAVs, mission and planner.
#include <cstdio>
#include <iostream>
#include <map>

#include "commands.h"
#include "uavplan/core/units.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"
#include "uavplan/planning/registry.h"

namespace uavplan::cli {
namespace {

const char* shape_name(const Obstacle& o) {
  switch (o.index()) {
    case 0: return "sphere";
    case 1: return "cylinder";
    case 2: return "box";
    default: return "prism";
  }
}

int run_info(const std::string& path) {
  Scenario sc;
  try {
    sc = load_scenario(path);
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  const World& w = sc.world;
  const Vec3 lo = w.bounds().min, hi = w.bounds().max;
  std::printf("scenario  %s (version %d)\n", sc.name.c_str(), sc.version);
  std::printf("bounds    [%g, %g, %g] .. [%g, %g, %g] m\n", lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
  std::map<std::string, int> counts;
  for (const auto& o : w.obstacles()) ++counts[shape_name(o)];
  std::printf("obstacles %zu", w.obstacles().size());
  for (const auto& [k, n] : counts) std::printf("  %s %d", k.c_str(), n);
  std::printf("\nthreats   %zu radar\n", w.radars().size());
  if (const TerrainGrid* t = w.terrain())
    std::printf("terrain   %d x %d cells of %g m, max height %g m\n", t->nx(), t->ny(), t->cell_m(), t->max_height());
  else
    std::printf("terrain   none\n");
  std::printf("moving    %zu\n", w.moving().size());
  if (sc.origin) std::printf("origin    lat %.7f lon %.7f alt %.2f m\n", sc.origin->lat_deg, sc.origin->lon_deg, sc.origin->alt_m);
  std::printf("mission   %s, separation %g m, %zu waypoints\n", std::string(to_string(sc.mission.type)).c_str(),
              sc.mission.separation_m, sc.mission.waypoints.size());
  std::printf("planner   %s", sc.planner.algorithm.c_str());
  for (const auto& [k, v] : sc.planner.params) std::printf(" %s=%s", k.c_str(), v.c_str());
  std::printf("\nuavs      %zu\n", sc.uavs.size());
  for (const auto& u : sc.uavs) {
    std::printf("  %-10s start (%g, %g, %g)", u.id.c_str(), u.start.x(), u.start.y(), u.start.z());
    if (u.goal) std::printf(" goal (%g, %g, %g)", u.goal->x(), u.goal->y(), u.goal->z());
    std::printf(" r %g m, %g m/s, turn %g deg, climb %g deg\n", u.radius_m, u.speed.cruise_mps,
                rad_to_deg(u.max_turn_rad), rad_to_deg(u.max_climb_rad));
  }
  std::printf("planners available:");
  for (const auto& p : planner_catalog()) std::printf(" %s", p.name.c_str());
  std::printf("\n");
  return kExitOk;
}

}  // namespace

void add_info_command(CLI::App& app, std::function<int()>& run) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "Summarise a scenario: world, UAVs, mission, planner");
  cmd->add_option("scenario", *path, "Scenario file")->required();
  cmd->callback([path, &run] { run = [path] { return run_info(*path); }; });
}

}  // namespace uavplan::cli
