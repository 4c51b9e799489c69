#include "uavplan/experiments/results.h"
#include "uavplan/core/text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

namespace uavplan {
namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string number(double x, int decimals) {
  if (!std::isfinite(x)) return "";
  return strf("%.*f", decimals, x);
}

std::vector<const RunRecord*> by_run(const std::vector<RunRecord>& records) {
  std::vector<const RunRecord*> v;
  v.reserve(records.size());
  for (const auto& r : records) v.push_back(&r);
  std::sort(v.begin(), v.end(), [](const RunRecord* a, const RunRecord* b) { return a->spec.index < b->spec.index; });
  return v;
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }
double number_of(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

}  // namespace

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const auto lo = static_cast<std::size_t>(pos);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - double(lo)) * (v[hi] - v[lo]);
}

std::string planner_name(const RunRecord& r) {
  return !r.spec.planner.empty() ? r.spec.planner : !r.outcome.algorithm.empty() ? r.outcome.algorithm : "(scenario's)";
}

std::string results_csv(const std::vector<RunRecord>& records) {
  std::string out =
      "run,scenario,planner,seed,params,status,verified,violations,uavs,uavs_solved,length_m,flight_time_s,expansions,"
      "min_separation_m,plan_file,reason,message\n";
  for (const RunRecord* r : by_run(records)) {
    const RunOutcome& o = r->outcome;
    const std::vector<std::string> f = {std::to_string(r->spec.index),
                                        r->spec.scenario,
                                        planner_name(*r),
                                        std::to_string(r->spec.seed),
                                        params_text(r->spec.params),
                                        std::string(to_string(o.status)),
                                        o.verified ? "1" : "0",
                                        std::to_string(o.violations),
                                        std::to_string(o.uavs),
                                        std::to_string(o.uavs_solved),
                                        number(o.length_m, 3),
                                        number(o.flight_time_s, 3),
                                        std::to_string(o.expansions),
                                        number(o.min_separation_m, 3),
                                        r->plan_file,
                                        std::string(to_string(o.reason)),
                                        o.message};
    for (std::size_t i = 0; i < f.size(); ++i) out += (i ? "," : "") + csv_field(f[i]);
    out += '\n';
  }
  return out;
}

std::string timings_csv(const std::vector<RunRecord>& records) {
  std::string out = "run,plan_ms,wall_ms\n";
  for (const RunRecord* r : by_run(records))
    out += std::to_string(r->spec.index) + "," + number(r->outcome.plan_ms, 3) + "," + number(r->outcome.wall_ms, 3) +
           "\n";
  return out;
}

std::string journal_line(const RunRecord& r) {
  const RunOutcome& o = r.outcome;
  nlohmann::json params = nlohmann::json::array();
  for (const auto& [k, v] : r.spec.params) params.push_back({k, v});
  const nlohmann::json j = {{"run", r.spec.index},
                            {"scenario", r.spec.scenario},
                            {"scenario_fingerprint", r.spec.scenario_fingerprint},
                            {"planner", r.spec.planner},
                            {"seed", r.spec.seed},
                            {"params", params},
                            {"status", to_string(o.status)},
                            {"reason", to_string(o.reason)},
                            {"algorithm", o.algorithm},
                            {"verified", o.verified},
                            {"violations", o.violations},
                            {"uavs", o.uavs},
                            {"uavs_solved", o.uavs_solved},
                            {"length_m", number_or_null(o.length_m)},
                            {"flight_time_s", number_or_null(o.flight_time_s)},
                            {"expansions", o.expansions},
                            {"min_separation_m", number_or_null(o.min_separation_m)},
                            {"message", o.message},
                            {"plan_ms", o.plan_ms},
                            {"wall_ms", o.wall_ms},
                            {"plan_file", r.plan_file}};
  // Invalid UTF-8 in a message (from a file) is replaced, never a throw.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::optional<RunRecord> parse_journal_line(const std::string& line) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  try {
    RunRecord r;
    r.spec.index = j.at("run").get<std::size_t>();
    r.spec.scenario = j.at("scenario").get<std::string>();
    r.spec.scenario_fingerprint = j.value("scenario_fingerprint", std::string());
    r.spec.planner = j.at("planner").get<std::string>();
    r.spec.seed = j.at("seed").get<std::uint64_t>();
    for (const auto& p : j.at("params"))
      r.spec.params.emplace_back(p.at(0).get<std::string>(), p.at(1).get<std::string>());
    RunOutcome& o = r.outcome;
    const auto status = run_status_from_string(j.at("status").get<std::string>());
    const auto reason = reason_from_string(j.value("reason", std::string("none")));
    if (!status || !reason) return std::nullopt;
    o.status = *status;
    o.reason = *reason;
    o.algorithm = j.at("algorithm").get<std::string>();
    o.verified = j.at("verified").get<bool>();
    o.violations = j.at("violations").get<std::size_t>();
    o.uavs = j.at("uavs").get<std::size_t>();
    o.uavs_solved = j.at("uavs_solved").get<std::size_t>();
    o.length_m = number_of(j.at("length_m"));
    o.flight_time_s = number_of(j.at("flight_time_s"));
    o.expansions = j.at("expansions").get<std::uint64_t>();
    o.min_separation_m = number_of(j.at("min_separation_m"));
    o.message = j.at("message").get<std::string>();
    o.plan_ms = j.at("plan_ms").get<double>();
    o.wall_ms = j.at("wall_ms").get<double>();
    r.plan_file = j.at("plan_file").get<std::string>();
    return r;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

bool same_run(const RunSpec& a, const RunSpec& b) {
  return a.index == b.index && a.scenario == b.scenario && a.scenario_fingerprint == b.scenario_fingerprint &&
         a.planner == b.planner && a.seed == b.seed && a.params == b.params;
}

std::string summary_table(const std::vector<RunRecord>& records) {
  struct Group {
    std::size_t runs = 0, solved = 0, verified = 0;
    std::vector<double> ms;
    double length_sum = 0.0;
    std::size_t lengths = 0;
  };
  // One row per planner, parameter setting and scenario: runs of different settings are
  // different experiments (merged, a sweep over cell_m showed one mean of all of them).
  using Key = std::tuple<std::string, std::string, std::string>;
  std::map<Key, Group> groups;
  for (const RunRecord& r : records) {
    const std::string params = r.spec.params.empty() ? "-" : params_text(r.spec.params);
    Group& g = groups[{planner_name(r), params, std::filesystem::path(r.spec.scenario).filename().string()}];
    ++g.runs;
    g.solved += r.outcome.status == RunStatus::solved;
    g.verified += r.outcome.status == RunStatus::solved && r.outcome.verified;
    g.ms.push_back(r.outcome.plan_ms);
    if (r.outcome.status == RunStatus::solved && std::isfinite(r.outcome.length_m)) {
      g.length_sum += r.outcome.length_m;
      ++g.lengths;
    }
  }
  std::size_t params_w = 6;
  for (const auto& [key, g] : groups) params_w = std::max(params_w, std::get<1>(key).size());
  std::string out;
  const int pw = static_cast<int>(std::min<std::size_t>(params_w, 200));
  out += strf("%-16s %-*s %-28s %6s %7s %8s %10s %10s %14s\n", "planner", pw, "params", "scenario", "runs", "solved",
              "verified", "median_ms", "p95_ms", "mean_length_m");
  for (const auto& [key, g] : groups) {
    const auto& [planner, params, scenario] = key;
    out += strf("%-16s %-*s %-28s %6zu %7zu %8zu %10.2f %10.2f %14s\n", planner.c_str(), pw, params.c_str(),
                scenario.c_str(), g.runs, g.solved, g.verified, quantile(g.ms, 0.5), quantile(g.ms, 0.95),
                g.lengths ? number(g.length_sum / double(g.lengths), 1).c_str() : "-");
  }
  return out;
}

}  // namespace uavplan
