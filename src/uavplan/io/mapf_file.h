// libMultiRobotPlanning's multi-agent path finding files (the format its benchmark instances and
// checkers use): an instance (`map: {dimensions: [W, H], obstacles: [[x, y], ...]}`,
// `agents: [{name, start: [x, y], goal: [x, y]}, ...]`) and a solution (`statistics: {cost,
// makespan, runtime}`, `schedule: {NAME: [{x, y, t}, ...]}`).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "uavplan/coordination/spacetime/mapf.h"

namespace uavplan {

struct MapfInstance {
  int width = 0, height = 0;
  std::vector<char> blocked;  // blocked[y * width + x]
  std::vector<std::string> names;
  std::vector<std::array<int, 2>> starts, goals;  // (x, y)

  MapfProblem problem() const;  // 4-connected grid; vertex y * width + x
  std::size_t cell_index(const std::array<int, 2>& c) const {
    return static_cast<std::size_t>(c[1]) * static_cast<std::size_t>(width) + static_cast<std::size_t>(c[0]);
  }
};

// Throws InputError naming the file, the line and the key ("agents[3].start: on an obstacle").
MapfInstance read_mapf_instance(const std::string& path);
MapfInstance parse_mapf_instance(const std::string& text, const std::string& file);

// The solution file: every agent's cells from t = 0 to its arrival (names escaped as YAML
// strings); `runtime_s` as measured by the caller.
std::string mapf_solution_yaml(const MapfInstance& instance, const MapfResult& result, double runtime_s);

}  // namespace uavplan
