#include "uavplan/experiments/ompl_log.h"
#include "uavplan/core/text.h"

#include <cmath>
#include <cstdio>
#include <map>

namespace uavplan {
namespace {

std::string no_spaces(std::string s) {
  for (char& c : s)
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = '_';
  return s.empty() ? "_" : s;
}

std::string real(double x) {
  if (!std::isfinite(x)) return "";
  return strf("%.9g", x);
}

const char* kRunProperties[] = {
    "time REAL",    "solved BOOLEAN",     "correct solution BOOLEAN", "solution length REAL", "graph states INTEGER",
    "seed INTEGER", "violations INTEGER", "flight time REAL",         "min separation REAL"};

std::string measurement(const RunRecord& r) {
  const RunOutcome& o = r.outcome;
  const bool solved = o.status == RunStatus::solved;
  const std::string values[] = {real(o.plan_ms / 1000.0),
                                solved ? "1" : "0",
                                solved ? (o.verified ? "1" : "0") : "",
                                solved ? real(o.length_m) : "",
                                std::to_string(o.expansions),
                                std::to_string(r.spec.seed),
                                std::to_string(o.violations),
                                solved ? real(o.flight_time_s) : "",
                                solved ? real(o.min_separation_m) : ""};
  std::string line;
  for (const std::string& v : values) line += v + "; ";
  return line + "\n";
}

}  // namespace

std::string ompl_planner_name(const RunRecord& r) {
  std::string name = planner_name(r);
  if (!r.spec.params.empty()) {
    std::string p;
    for (const auto& [k, v] : r.spec.params) p += (p.empty() ? "" : ",") + k + "=" + v;
    name += "[" + p + "]";
  }
  return no_spaces(name);
}

std::string ompl_log(const std::vector<RunRecord>& runs, const OmplLogHeader& h) {
  // Planners in the order of their first run.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const RunRecord*>> by_planner;
  for (const RunRecord& r : runs) {
    const std::string name = ompl_planner_name(r);
    if (!by_planner.count(name)) order.push_back(name);
    by_planner[name].push_back(&r);
  }
  std::string out = "uavplan version 0.1.0\n";
  out += "Experiment " + no_spaces(h.experiment) + "\n";
  out += "Running on " + no_spaces(h.host) + "\n";
  out += "Starting at " + h.date + "\n";
  out += "<<<|\n" + h.setup + (h.setup.empty() || h.setup.back() == '\n' ? "" : "\n") + "|>>>\n";
  out += std::to_string(runs.empty() ? 0 : runs.front().spec.seed) + " is the random seed\n";
  out += (h.time_limit_s > 0.0 ? real(h.time_limit_s) : std::string("inf")) + " seconds per run\n";
  out += real(h.memory_limit_mb) + " MB per run\n";
  std::size_t common = order.empty() ? 0 : by_planner[order.front()].size();
  for (const auto& name : order)
    if (by_planner[name].size() != common) common = 0;
  if (common) out += std::to_string(common) + " runs per planner\n";
  double spent_ms = 0.0;
  for (const RunRecord& r : runs) spent_ms += r.outcome.wall_ms;
  out += real(spent_ms / 1000.0) + " seconds spent to collect the data\n";
  out += std::to_string(order.size()) + " planners\n";
  for (const std::string& name : order) {
    const auto& rs = by_planner[name];
    out += name + "\n";
    out += std::to_string(rs.front()->spec.params.size()) + " common properties\n";
    for (const auto& [k, v] : rs.front()->spec.params) out += no_spaces(k) + " = " + no_spaces(v) + "\n";
    out += std::to_string(std::size(kRunProperties)) + " properties for each run\n";
    for (const char* p : kRunProperties) out += std::string(p) + "\n";
    out += std::to_string(rs.size()) + " runs\n";
    for (const RunRecord* r : rs) out += measurement(*r);
    out += ".\n";
  }
  return out;
}

}  // namespace uavplan
