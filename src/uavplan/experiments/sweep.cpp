#include "uavplan/experiments/sweep.h"

#include <glob.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "uavplan/coordination/mission.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kMaxSeedCount = 1'000'000;
constexpr std::size_t kMaxRuns = 100'000'000;

struct Reader {
  const std::string& file;

  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& what) const {
    throw InputError(file, n.IsDefined() ? n.Mark().line + 1 : 0, key, what);
  }
  std::string scalar(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(n, key, "expected a value");
    return n.Scalar();
  }
  std::vector<std::string> values(const YAML::Node& n, const std::string& key) const {
    std::vector<std::string> out;
    if (n.IsScalar()) return {n.Scalar()};
    if (!n.IsSequence() || n.size() == 0) fail(n, key, "expected a value or a non-empty list of values");
    for (std::size_t i = 0; i < n.size(); ++i) out.push_back(scalar(n[i], key + "[" + std::to_string(i) + "]"));
    return out;
  }
  ParamGrid grid(const YAML::Node& n, const std::string& key) const {
    if (!n.IsMap()) fail(n, key, "expected a map of parameter: [values]");
    ParamGrid g;
    for (const auto& kv : n) {
      const std::string k = scalar(kv.first, key);
      if (k.empty()) fail(kv.first, key, "empty parameter name");
      g.push_back({k, values(kv.second, key + "." + k), kv.first.Mark().line + 1});
    }
    return g;
  }
};

std::vector<std::string> expand_glob(const std::string& pattern) {
  glob_t g{};
  std::vector<std::string> out;
  if (::glob(pattern.c_str(), GLOB_NOSORT, nullptr, &g) == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);
  ::globfree(&g);
  std::sort(out.begin(), out.end());
  return out;
}

void read_scenarios(const Reader& r, const YAML::Node& n, const fs::path& base, Sweep& s) {
  if (!n.IsDefined()) throw InputError(r.file, 0, "scenarios", "missing: name the scenario files (or globs) to run");
  const std::vector<std::string> given = r.values(n, "scenarios");
  for (std::size_t i = 0; i < given.size(); ++i) {
    const YAML::Node& item = n.IsSequence() ? n[i] : n;
    const std::string key = "scenarios[" + std::to_string(i) + "]";
    const fs::path p = fs::path(given[i]).is_absolute() ? fs::path(given[i]) : base / given[i];
    const bool pattern = given[i].find_first_of("*?[") != std::string::npos;
    std::vector<std::string> found = pattern ? expand_glob(p.string()) : std::vector<std::string>{p.string()};
    // A glob beside the sweep ("*.yaml") would match the sweep file itself.
    std::error_code ec;
    const fs::path self = fs::weakly_canonical(r.file, ec);
    std::erase_if(found, [&](const std::string& f) { return pattern && fs::weakly_canonical(f, ec) == self; });
    if (pattern && found.empty()) r.fail(item, key, "'" + given[i] + "' matches no file");
    if (!pattern && !fs::is_regular_file(p)) r.fail(item, key, "no such scenario file: " + p.string());
    for (auto& f : found) {
      // A file named twice (by two globs, or a glob and its name) is run once.
      const fs::path canon = fs::weakly_canonical(f, ec);
      if (std::any_of(s.scenarios.begin(), s.scenarios.end(),
                      [&](const std::string& g) { return fs::weakly_canonical(g, ec) == canon; }))
        continue;
      s.scenarios.push_back(std::move(f));
      s.scenario_lines.push_back(item.Mark().line + 1);
    }
  }
}

void read_planners(const Reader& r, const YAML::Node& n, Sweep& s) {
  if (!n.IsDefined()) {
    s.planners.push_back({});
    return;
  }
  if (n.IsScalar()) {
    s.planners.push_back({n.Scalar(), {}, n.Mark().line + 1});
    return;
  }
  if (!n.IsSequence() || n.size() == 0) r.fail(n, "planners", "expected a non-empty list of planner names");
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string key = "planners[" + std::to_string(i) + "]";
    const YAML::Node& p = n[i];
    SweepPlanner sp{{}, {}, p.Mark().line + 1};
    if (p.IsScalar()) {
      sp.name = p.Scalar();
    } else if (p.IsMap()) {
      for (const auto& kv : p) {
        const std::string k = r.scalar(kv.first, key);
        if (k == "name")
          sp.name = r.scalar(kv.second, key + ".name");
        else if (k == "params")
          sp.params = r.grid(kv.second, key + ".params");
        else
          r.fail(kv.first, key + "." + k, "unknown key (expected name, params)");
      }
      if (sp.name.empty()) r.fail(p, key, "a planner with params needs a name");
    } else {
      r.fail(p, key, "expected a planner name or {name, params}");
    }
    s.planners.push_back(std::move(sp));
  }
}

void read_seeds(const Reader& r, const YAML::Node& n, Sweep& s) {
  auto as_seed = [&](const YAML::Node& v, const std::string& key) {
    try {
      const long long x = v.as<long long>();
      if (x < 0) r.fail(v, key, "a seed is a non-negative integer");
      return static_cast<std::uint64_t>(x);
    } catch (const YAML::Exception&) {
      r.fail(v, key, "expected a non-negative integer, got '" + r.scalar(v, key) + "'");
    }
  };
  if (!n.IsDefined()) {
    s.seeds = {1};
  } else if (n.IsScalar()) {
    const std::uint64_t count = as_seed(n, "seeds");
    if (count == 0 || count > kMaxSeedCount) r.fail(n, "seeds", "a count of seeds is 1 to 1000000");
    for (std::uint64_t k = 1; k <= count; ++k) s.seeds.push_back(k);
  } else if (n.IsSequence() && n.size() > 0) {
    for (std::size_t i = 0; i < n.size(); ++i) s.seeds.push_back(as_seed(n[i], "seeds[" + std::to_string(i) + "]"));
  } else {
    r.fail(n, "seeds", "expected a count or a non-empty list of seeds");
  }
}

// The k-th combination of a grid, the last key varying fastest.
void append_combination(const ParamGrid& g, std::size_t k, ParamSetting& out) {
  std::vector<std::size_t> idx(g.size());
  for (std::size_t i = g.size(); i-- > 0;) {
    idx[i] = k % g[i].values.size();
    k /= g[i].values.size();
  }
  for (std::size_t i = 0; i < g.size(); ++i) out.emplace_back(g[i].key, g[i].values[idx[i]]);
}

bool dotted(const std::string& key) { return key.find_first_of(".[") != std::string::npos; }

bool mission_reads(const Scenario& sc, const std::string& key) {
  const Mission* m = find_mission(sc.mission.type);
  if (!m) return false;
  const auto keys = m->declaration().parameters;
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace

Sweep parse_sweep(const std::string& text, const std::string& source_path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source_path, e.mark.line + 1, "", e.msg);
  }
  const Reader r{source_path};
  if (!root.IsMap()) throw InputError(source_path, 0, "", "a sweep is a map (scenarios, planners, seeds, params)");
  static const std::set<std::string> known = {"name", "scenarios", "planners", "seeds", "params", "time_limit_s"};
  for (const auto& kv : root) {
    const std::string k = r.scalar(kv.first, "");
    if (!known.count(k))
      r.fail(kv.first, k, "unknown key (expected name, scenarios, planners, seeds, params, time_limit_s)");
  }
  Sweep s;
  s.source = source_path;
  s.name = root["name"].IsDefined() ? r.scalar(root["name"], "name") : fs::path(source_path).stem().string();
  read_scenarios(r, root["scenarios"], fs::path(source_path).parent_path(), s);
  read_planners(r, root["planners"], s);
  read_seeds(r, root["seeds"], s);
  if (root["params"].IsDefined()) s.params = r.grid(root["params"], "params");
  if (const YAML::Node t = root["time_limit_s"]; t.IsDefined()) {
    try {
      s.time_limit_s = t.as<double>();
    } catch (const YAML::Exception&) {
      r.fail(t, "time_limit_s", "expected a number of seconds");
    }
    if (!(s.time_limit_s > 0.0 && s.time_limit_s < 1e7))
      r.fail(t, "time_limit_s", "must be a positive number of seconds");
  }
  std::size_t per_scenario = 0;
  for (const SweepPlanner& p : s.planners) per_scenario += grid_size(p.params);
  const double total =
      double(s.scenarios.size()) * double(per_scenario) * double(grid_size(s.params)) * double(s.seeds.size());
  if (total == 0.0) throw InputError(source_path, 0, "", "the sweep's product is empty: no run to do");
  if (total > double(kMaxRuns)) throw InputError(source_path, 0, "", "the sweep has over 100000000 runs");
  return s;
}

Sweep load_sweep(const std::string& path) { return parse_sweep(read_text_file(path), path); }

std::size_t grid_size(const ParamGrid& g) {
  std::size_t n = 1;
  for (const auto& e : g) n *= e.values.size();
  return n;
}

std::size_t run_count(const Sweep& sweep) {
  std::size_t per_scenario = 0;
  for (const SweepPlanner& p : sweep.planners) per_scenario += grid_size(p.params);
  return sweep.scenarios.size() * per_scenario * grid_size(sweep.params) * sweep.seeds.size();
}

std::vector<RunSpec> expand_runs(const Sweep& sweep) {
  std::vector<RunSpec> runs;
  runs.reserve(run_count(sweep));
  for (const std::string& sc : sweep.scenarios) {
    const std::string fingerprint = content_fingerprint(read_text_file(sc));
    for (const SweepPlanner& p : sweep.planners)
      for (std::size_t pk = 0; pk < grid_size(p.params); ++pk)
        for (std::size_t gk = 0; gk < grid_size(sweep.params); ++gk)
          for (const std::uint64_t seed : sweep.seeds) {
            RunSpec r;
            r.index = runs.size();
            r.scenario = sc;
            r.scenario_fingerprint = fingerprint;
            r.planner = p.name;
            r.seed = seed;
            append_combination(sweep.params, gk, r.params);
            append_combination(p.params, pk, r.params);
            runs.push_back(std::move(r));
          }
  }
  return runs;
}

std::string params_text(const ParamSetting& params) {
  std::string s;
  for (const auto& [k, v] : params) {
    if (!s.empty()) s += ';';
    s += k + "=" + v;
  }
  return s;
}

void check_sweep(const Sweep& sweep) {
  std::set<std::string> names;
  for (const PlannerInfo& p : planner_catalog()) names.insert(p.name);
  for (std::size_t pi = 0; pi < sweep.planners.size(); ++pi) {
    const SweepPlanner& p = sweep.planners[pi];
    if (!p.name.empty() && !names.count(p.name)) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
      throw InputError(sweep.source, p.line, "planners[" + std::to_string(pi) + "]",
                       "unknown planner '" + p.name + "' (known: " + known + ")");
    }
  }
  for (std::size_t si = 0; si < sweep.scenarios.size(); ++si) {
    const std::string skey = "scenarios[" + std::to_string(si) + "]";
    Scenario sc;
    std::string text;
    try {
      text = read_text_file(sweep.scenarios[si]);
      sc = parse_scenario(text, sweep.scenarios[si]);
    } catch (const InputError& e) {
      throw InputError(sweep.source, sweep.scenario_lines[si], skey, e.what());
    }
    for (std::size_t pi = 0; pi < sweep.planners.size(); ++pi) {
      const SweepPlanner& p = sweep.planners[pi];
      std::string algorithm;
      try {
        algorithm = mission_algorithm(sc, p.name.empty() ? std::nullopt : std::optional<std::string>(p.name));
      } catch (const std::invalid_argument& e) {
        throw InputError(sweep.source, p.line, "planners[" + std::to_string(pi) + "]",
                         sweep.scenarios[si] + ": " + e.what());
      }
      auto check = [&](const GridEntry& g, const std::string& key) {
        for (const std::string& v : g.values) {
          if (dotted(g.key)) {
            try {
              parse_scenario(text, sweep.scenarios[si], {{g.key, v}});
            } catch (const InputError& e) {
              throw InputError(sweep.source, g.line, key, e.what());
            }
          } else if (!planner_accepts(algorithm, g.key, v) && !mission_reads(sc, g.key)) {
            throw InputError(
                sweep.source, g.line, key,
                "'" + v + "' is not a value of a parameter of " + algorithm + " (on " + sweep.scenarios[si] + ")");
          }
        }
      };
      for (const GridEntry& g : sweep.params) check(g, "params." + g.key);
      for (const GridEntry& g : p.params) check(g, "planners[" + std::to_string(pi) + "].params." + g.key);
    }
  }
}

}  // namespace uavplan
