// Planner parameters as given in a scenario's `planner.params` or on the command line, read
// into a planner's options struct with range checks; unknown keys are errors (usually typos).
#pragma once

#include <map>
#include <set>
#include <string>

namespace uavplan {

using Params = std::map<std::string, std::string>;

// While one is alive, every ParamReader on this thread records the keys it reads and their
// defaults here (registry.h's planner_parameters lists a planner's parameters this way).
class ParamListing {
 public:
  ParamListing();
  ~ParamListing();
  ParamListing(const ParamListing&) = delete;
  ParamListing& operator=(const ParamListing&) = delete;
  std::map<std::string, std::string> defaults;  // key -> default value as text
};

class ParamReader {
 public:
  ParamReader(const Params& params, std::string planner) : params_(params), planner_(std::move(planner)) {}

  // Each throws std::invalid_argument naming the key when the value is malformed or out of range.
  double number(const std::string& key, double fallback, double lo, double hi);
  int integer(const std::string& key, int fallback, int lo, int hi);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);

  // Throws std::invalid_argument when a given key was never read.
  void finish() const;

 private:
  const std::string* find(const std::string& key, const std::string& fallback);
  const Params& params_;
  std::string planner_;
  std::set<std::string> known_;
};

}  // namespace uavplan
