#include "soak_runner.h"
#include "claims.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/random_worlds.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/planning/registry.h"

namespace uavplan::bench {

std::string run_soak(const SoakOptions& opt, bool* all_held) {
  struct Kind {
    std::string algorithm;
    std::string mission;
  };
  std::vector<Kind> kinds;
  for (const auto& p : planner_catalog()) kinds.push_back({p.name, "independent"});
  kinds.push_back({"apf", "group"});
  kinds.push_back({"directional_astar", "rendezvous"});
  std::string out;
  char buf[200];
  std::snprintf(buf, sizeof buf, "soak: %d random worlds per row, seed %llu, %g s stop per plan\n", opt.worlds,
                static_cast<unsigned long long>(opt.seed), opt.stop_s);
  out += buf;
  std::snprintf(buf, sizeof buf, "%-20s %-12s %7s %8s %10s %10s %10s %5s\n", "planner", "mission", "uavs", "solved",
                "bad_claims", "median_ms", "max_ms", "late");
  out += buf;
  bool held = true;
  for (const Kind& k : kinds) {
    Claims claims;
    std::vector<double> ms;
    RandomWorldOptions wo;
    wo.mission = k.mission;
    for (int w = 0; w < opt.worlds; ++w) {
      const Scenario sc = random_world(opt.seed * 1000003 + static_cast<std::uint64_t>(w), wo);
      MissionOptions mo;
      mo.algorithm = k.algorithm;
      mo.seed = opt.seed + static_cast<std::uint64_t>(w);
      mo.stop = StopCondition::time_limit(opt.stop_s);
      const auto t0 = std::chrono::steady_clock::now();
      const Plan plan = plan_mission(sc, mo);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      claims.add(plan, verify_plan(sc, plan));
    }
    std::sort(ms.begin(), ms.end());
    const auto late =
        std::count_if(ms.begin(), ms.end(), [&](double t) { return t > 1000.0 * (opt.stop_s + kSoakGraceS); });
    held = held && claims.bad == 0 && late == 0;
    std::snprintf(buf, sizeof buf, "%-20s %-12s %7d %8d %10d %10.2f %10.1f %5d\n", k.algorithm.c_str(),
                  k.mission.c_str(), claims.uavs, claims.solved, claims.bad, ms.empty() ? 0.0 : ms[ms.size() / 2],
                  ms.empty() ? 0.0 : ms.back(), static_cast<int>(late));
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "(late: plans that ended more than %g s after their stop)\n", kSoakGraceS);
  out += buf;
  if (all_held) *all_held = held;
  return out;
}

}  // namespace uavplan::bench
