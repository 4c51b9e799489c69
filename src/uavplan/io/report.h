// The HTML report: one self-contained offline page with a 3-D view of the world and the routes
// (three.js: axes in metres, a north arrow and a scale bar, radar shells, moving obstacles and
// their tracks, a time slider that moves the UAVs), charts of altitude, speed and separation to
// the nearest UAV over time and each UAV's height above ground along its route (uPlot), the
// metrics tables and the verifier's verdict.
#pragma once

#include <string>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {

struct ReportOptions {
  int series_samples = 600;        // time samples of the charts
  int profile_samples = 400;       // distance samples of each UAV's height profile
  int max_terrain_cells = 65'536;  // larger terrains are shown block-wise (each block's highest cell)
  // A flight of the plan (`uavplan fly`'s flown.json): its tracks drawn beside the planned routes
  // (dashed, in each UAV's colour), at most max_flown_rows rows each.
  const Plan* flown = nullptr;
  int max_flown_rows = 4000;
};

// The data the page draws, as JSON: world, trajectories, time series, height profiles, metrics
// (computed from the trajectories, not read from the plan), verification; the flown tracks.
std::string report_data_json(const Scenario& sc, const Plan& plan, const std::vector<Violation>& violations,
                             const ReportOptions& opt = {});

// The whole page: the data and the bundled viewer (script and style) inlined.
std::string report_html(const Scenario& sc, const Plan& plan, const std::vector<Violation>& violations,
                        const ReportOptions& opt = {});

}  // namespace uavplan
