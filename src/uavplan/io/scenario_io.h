// Scenario files (YAML, or the same structure in JSON), version 1 of the public contract.
// Every error is an InputError naming the file, the line and key, and what is wrong;
// unknown keys are errors (they are usually typos).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/core/stop.h"

namespace uavplan {

// What a scenario may hold, so that no file that loads can exhaust the machine (each is an
// error at load, naming the key):
inline constexpr double kMaxCoordinate_m = 1e9;                // |any coordinate|, velocity, range
inline constexpr double kMaxFlight_s = 1e6;                    // straight route / cruise speed
inline constexpr double kMaxFleetFlight_s = 2e6;               // the same, added over the UAVs
inline constexpr std::size_t kMaxTerrainCells = 16'777'216;    // 4096 x 4096
inline constexpr std::size_t kMaxScenarioValues = 20'000'000;  // values the file expands to (YAML aliases)
// Values written in the file, counted before it is parsed: the YAML tree takes about 500 bytes
// a value, so this keeps a scenario under about 2 GB (an inline terrain of 2000 x 2000 cells).
inline constexpr std::size_t kMaxWrittenValues = 4'000'000;
inline constexpr double kMinStep_s = 1e-3;  // mission.step_s

// "key=value" overrides from the command line: a bare key sets planner.params.KEY; a dotted
// path (a.b[2].c) sets that place of the scenario; the value is read as YAML.
using Overrides = std::vector<std::pair<std::string, std::string>>;

// `stop` bounds what loading may take: its memory cap and deadline hold while an elevation model is
// read (a window past the cap is an InputError naming --max-memory; Stopped is thrown when the
// deadline passes or the run is interrupted between strips).
Scenario load_scenario(const std::string& path, const Overrides& overrides = {}, const StopCondition& stop = {});
Scenario parse_scenario(const std::string& text, const std::string& source_name, const Overrides& overrides = {},
                        const StopCondition& stop = {});

}  // namespace uavplan
