// The HTML report: one self-contained offline page with a 3-D view of the world and the routes
// (three.js, a time slider that moves the UAVs), charts of altitude, speed and separation to the
// nearest UAV over time (uPlot), the metrics table and the verifier's verdict.
#pragma once

#include <string>
#include <vector>

#include "uavplan/coordination/plan.h"
#include "uavplan/coordination/scenario.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {

struct ReportOptions {
  int series_samples = 600;          // time samples of the charts
  int max_terrain_cells = 250'000;   // larger terrains are shown block-wise (each block's highest cell)
};

// The data the page draws, as JSON: world, trajectories, time series, metrics, verification.
std::string report_data_json(const Scenario& sc, const Plan& plan, const std::vector<Violation>& violations,
                             const ReportOptions& opt = {});

// The whole page: the data and the bundled viewer (script and style) inlined.
std::string report_html(const Scenario& sc, const Plan& plan, const std::vector<Violation>& violations,
                        const ReportOptions& opt = {});

}  // namespace uavplan
