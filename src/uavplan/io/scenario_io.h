// Scenario files (YAML, or the same structure in JSON), version 1 of the public contract.
// Every error is an InputError naming the file, the line and key, and what is wrong;
// unknown keys are errors (they are usually typos).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "uavplan/coordination/scenario.h"

namespace uavplan {

// "key=value" overrides from the command line: a bare key sets planner.params.KEY; a dotted
// path (a.b[2].c) sets that place of the scenario; the value is read as YAML.
using Overrides = std::vector<std::pair<std::string, std::string>>;

Scenario load_scenario(const std::string& path, const Overrides& overrides = {});
Scenario parse_scenario(const std::string& text, const std::string& source_name, const Overrides& overrides = {});

}  // namespace uavplan
