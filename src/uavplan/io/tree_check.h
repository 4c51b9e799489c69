// Checks of a parsed YAML (or JSON) tree that the parsers do not make: duplicate keys (yaml-cpp
// keeps the first, JSON readers the last: one file, two meanings) and how many values the tree
// expands to through aliases (a few lines can name billions). And the line of a key path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

namespace uavplan {

// Throws InputError naming the file, the line and the key path.
void check_tree(const YAML::Node& root, const std::string& file, std::size_t max_values);

// The 1-based line of a key path such as "uavs[2].trajectory[7]" in the tree; 0 when not there.
int line_of(const YAML::Node& root, const std::string& path);

}  // namespace uavplan
