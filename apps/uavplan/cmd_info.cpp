// uavplan info SCENARIO: a summary of a scenario's world, UAVs, mission and planner.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>

#include "commands.h"
#include "uavplan/coordination/mission.h"
#include "uavplan/coordination/planning_view.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"
#include "uavplan/planning/registry.h"

namespace uavplan::cli {
namespace {

void print_world(const Scenario& sc) {
  const World& w = sc.world;
  const Vec3 lo = w.bounds().min, hi = w.bounds().max;
  std::printf("scenario  %s (version %d)\n", sc.name.c_str(), sc.version);
  std::printf("bounds    [%g, %g, %g] .. [%g, %g, %g] m\n", lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
  std::map<std::string, int> counts;
  for (const auto& o : w.obstacles()) ++counts[std::string(shape_name(o))];
  std::printf("obstacles %zu", w.obstacles().size());
  for (const auto& [k, n] : counts) std::printf("  %s %d", k.c_str(), n);
  std::printf("\nthreats   %zu radar\n", w.radars().size());
  if (const TerrainGrid* t = w.terrain())
    std::printf("terrain   %d x %d cells of %g m, max height %g m\n", t->nx(), t->ny(), t->cell_m(), t->max_height());
  else
    std::printf("terrain   none\n");
  if (const auto& e = sc.elevation) {
    std::printf("  model   %s: %s raster, %d x %d pixels of %.3g m, %s\n", printable(e->file).c_str(),
                printable(e->driver).c_str(), e->raster_nx, e->raster_ny, e->raster_cell_m, printable(e->crs).c_str());
    std::printf(
        "          covers x %.0f..%.0f, y %.0f..%.0f m here; heights %.1f..%.1f m AMSL over the bounds; each "
        "cell the highest pixel it touches",
        e->extent_min.x(), e->extent_max.x(), e->extent_min.y(), e->extent_max.y(), e->min_amsl_m, e->max_amsl_m);
    if (e->nodata_filled > 0) std::printf("; %zu cells without data filled from their neighbours", e->nodata_filled);
    std::printf("\n");
  }
  if (!sc.airspace.empty()) {
    const auto inclusions =
        std::count_if(sc.airspace.begin(), sc.airspace.end(), [](const FenceZone& z) { return z.inclusion; });
    std::printf("airspace  %s from files (%td inclusion fence, %td no-fly)\n",
                count_text(sc.airspace.size(), "zone").c_str(), inclusions,
                static_cast<std::ptrdiff_t>(sc.airspace.size()) - inclusions);
  }
  std::printf("moving    %zu\n", w.moving().size());
  if (sc.origin)
    std::printf("origin    lat %.7f lon %.7f alt %.2f m\n", sc.origin->lat_deg, sc.origin->lon_deg, sc.origin->alt_m);
}

// The mission type and what it holds, in its own words (Mission::describe): via points, a shape,
// an airfield and task points.
void print_mission(const Scenario& sc) {
  const MissionSpec& m = sc.mission;
  const Mission* mission = find_mission(m.type);
  std::printf("mission   %s, separation %g m%s", printable(m.type).c_str(), m.separation_m,
              mission ? mission->describe(sc).c_str() : "");
  std::printf("\n");
}

// A UAV's line: where, how fast, its limits, what it senses and how it flies.
void print_uav(const UavSpec& u) {
  std::printf("  %-10s start (%g, %g, %g)", u.id.c_str(), u.start.x(), u.start.y(), u.start.z());
  if (u.goal) std::printf(" goal (%g, %g, %g)", u.goal->x(), u.goal->y(), u.goal->z());
  if (u.home) std::printf(" home (%g, %g, %g)", u.home->x(), u.home->y(), u.home->z());
  std::printf("\n             r %g m, speed %g..%g..%g m/s, turn %g deg, climb %g deg", u.radius_m, u.speed.min_mps,
              u.speed.cruise_mps, u.speed.max_mps, rad_to_deg(u.max_turn_rad), rad_to_deg(u.max_climb_rad));
  if (u.ceiling_m) std::printf(", ceiling %g m", *u.ceiling_m);
  if (u.min_agl_m > 0.0) std::printf(", min_agl %g m", u.min_agl_m);
  if (u.max_agl_m) std::printf(", max_agl %g m", *u.max_agl_m);
  if (u.clearance_m > 0.0) std::printf(", clearance %g m", u.clearance_m);
  if (u.sensor_range_m) std::printf(", sensor %g m", *u.sensor_range_m);
  if (u.max_turn_rate_rad_s) std::printf(", turn rate %g deg/s", rad_to_deg(*u.max_turn_rate_rad_s));
  if (u.max_climb_rate_mps) std::printf(", climb rate %g m/s", *u.max_climb_rate_mps);
  std::printf(", %s\n", u.model ? "autopilot model" : "point mass");
}

// The planner a plan would use, and the planners that can plan this mission (a group plans only
// with the fields; a route only with planners that pass via points, and where its via points have
// entry headings only with those that fly in along them).
void print_planners(const Scenario& sc) {
  std::printf("planner   %s", mission_algorithm(sc, std::nullopt).c_str());
  for (const auto& [k, v] : sc.planner.params) std::printf(" %s=%s", k.c_str(), v.c_str());
  std::printf("\nplanners for this mission:");
  for (const auto& p : planner_catalog())
    if (planner_refusal(sc, p).empty()) std::printf(" %s", p.name.c_str());
  std::printf("\n");
}

int run_info(const std::string& path) {
  Scenario sc;
  try {
    sc = load_scenario(path);
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  for (const std::string& hint : sc.hints) std::cerr << hint << "\n";
  print_world(sc);
  print_mission(sc);
  std::printf("uavs      %zu\n", sc.uavs.size());
  for (const auto& u : sc.uavs) print_uav(u);
  if (sc.default_min_agl_m > 0.0 && planning_min_agl_m(sc) == sc.default_min_agl_m) {
    if (sc.mission.cruise_agl_m)
      std::printf("min_agl   %g m above the ground for every UAV while planning (mission.cruise_agl %g m%s)\n",
                  sc.default_min_agl_m, *sc.mission.cruise_agl_m,
                  sc.default_min_agl_m < *sc.mission.cruise_agl_m ? ", less where the scenario has less room" : "");
    else
      std::printf(
          "min_agl   %g m above the ground for every UAV while planning (the default where a UAV takes off or "
          "lands and none sets min_agl; min_agl: 0 flies lower, mission.cruise_agl higher)\n",
          sc.default_min_agl_m);
  }
  print_planners(sc);
  return kExitOk;
}

// The mission types as their rooms declare them (keys, planners, parameters), or the planners
// as their options declare them (parameters with type, range, default, meaning).
int run_catalog(bool planners, bool markdown) {
  std::fputs((planners ? planner_catalog_text(markdown) : mission_catalog_text(markdown)).c_str(), stdout);
  return kExitOk;
}

}  // namespace

void add_info_command(CLI::App& app, std::function<int()>& run) {
  auto path = std::make_shared<std::string>();
  auto list = std::make_shared<bool>(false);
  auto planners = std::make_shared<bool>(false);
  auto markdown = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("info", "Summarise a scenario: world, UAVs, mission, planner");
  cmd->add_option("scenario", *path, "Scenario file");
  cmd->add_flag("--missions", *list, "List the mission types: their keys, planners and parameters");
  cmd->add_flag("--planners", *planners, "List the planners: their parameters with type, range, default, meaning");
  cmd->add_flag("--markdown", *markdown, "With --missions or --planners: as the docs' tables");
  cmd->callback([path, list, planners, markdown, &run] {
    const int asked = (path->empty() ? 0 : 1) + (*list ? 1 : 0) + (*planners ? 1 : 0);
    if (asked != 1) throw CLI::ValidationError("info", "give one of: a scenario file, --missions, --planners");
    if (*markdown && path->size()) throw CLI::ValidationError("info", "--markdown goes with --missions or --planners");
    run = [path, list, planners, markdown] {
      return path->empty() ? run_catalog(*planners, *markdown) : run_info(*path);
    };
  });
}

}  // namespace uavplan::cli
