// Checks of a parsed YAML (or JSON) tree that the parsers do not make: duplicate keys (yaml-cpp
// keeps the first, JSON readers the last: one file, two meanings) and how many values the tree
// expands to through aliases (a few lines can name billions). And the line of a key path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace uavplan {

// Throws InputError naming the file, the line and the key path.
void check_tree(const YAML::Node& root, const std::string& file, std::size_t max_values);

// A key path such as "uavs[2].trajectory[7]", step by step: a key, or a list index. `error`
// says where the text stops being one ("unclosed '['", "bad list index"); the steps before it
// are kept.
struct KeyPath {
  struct Step {
    std::string key;
    std::optional<std::size_t> index;
  };
  std::vector<Step> steps;
  std::string error;
};
KeyPath split_key_path(const std::string& path);

// The 1-based line of a key path such as "uavs[2].trajectory[7]" in the tree; 0 when not there.
int line_of(const YAML::Node& root, const std::string& path);

}  // namespace uavplan
