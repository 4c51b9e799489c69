// Planners by name.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "uavplan/planning/params.h"
#include "uavplan/planning/planner.h"

namespace uavplan {

// Throws std::invalid_argument for an unknown name or malformed parameters.
std::unique_ptr<Planner> make_planner(std::string_view name, const Params& params);

// Registered names with a one-line description each.
struct PlannerInfo {
  std::string name;
  std::string description;
  bool complete = true;    // finds a route whenever the grid it searches has one; local methods do not
  bool via_points = true;  // plans through via points (route missions)
  // A baseline whose constraints are penalties in its cost (P5's single-step PSO): it may fail
  // any problem, saying why, and never calls a route that breaks them solved.
  bool relaxed = false;
  bool entry_headings = false;  // honours a via point's entry heading (Problem::via_entry_heading_rad)
};
std::vector<PlannerInfo> planner_catalog();

// The planner's parameters as its options struct declares them (key, type, range, default as
// text: 0, nan or inf where the planner derives the value from the problem, meaning). Throws
// std::invalid_argument for an unknown name.
std::vector<ParamDecl> planner_parameters(std::string_view name);

// Whether the planner takes this parameter (the value checked too); false for an unknown planner.
bool planner_accepts(std::string_view name, const std::string& key, const std::string& value);

// Every planner with its parameters: `info --planners` (markdown = false) and docs/planners.md's
// tables (markdown = true).
std::string planner_catalog_text(bool markdown);

}  // namespace uavplan
