// A batch's results: results.csv (one row per run, the same bytes whatever ran it), timings.csv
// (wall-clock, apart), the journal a killed batch resumes from, and the summary table.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "uavplan/experiments/batch.h"

namespace uavplan {

// The planner a run names, else the one that planned it (the scenario's own).
std::string planner_name(const RunRecord& r);

// results.csv: run,scenario,planner,seed,params,status,verified,violations,uavs,uavs_solved,
// length_m,flight_time_s,expansions,min_separation_m,plan_file,reason,message. Rows by run number.
std::string results_csv(const std::vector<RunRecord>& records);
// timings.csv: run,plan_ms,wall_ms.
std::string timings_csv(const std::vector<RunRecord>& records);

// One line (JSON, no newline inside) per finished run; a line that does not parse (a batch
// killed while writing it) is nullopt.
std::string journal_line(const RunRecord& record);
std::optional<RunRecord> parse_journal_line(const std::string& line);

// Whether a journal's run is the sweep's run of the same number (same scenario file with the
// same content, planner, seed and parameters): a journal of another sweep, or of a scenario
// edited since, is not resumed (two versions of a file never mix in one results.csv).
bool same_run(const RunSpec& a, const RunSpec& b);

// The q-quantile of v, interpolated between its ranks (NaN for none).
double quantile(std::vector<double> v, double q);

// Per planner and scenario: runs, solved, verified, median and p95 plan time, mean length.
std::string summary_table(const std::vector<RunRecord>& records);

}  // namespace uavplan
