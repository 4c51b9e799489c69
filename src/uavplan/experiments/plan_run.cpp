#include "uavplan/experiments/plan_run.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan {

std::uint64_t default_memory_cap_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2;
}

std::uint64_t default_run_memory_cap_bytes(int jobs) {
  const unsigned n = jobs > 0 ? static_cast<unsigned>(jobs) : std::max(1u, std::thread::hardware_concurrency());
  return default_memory_cap_bytes() / n;
}

VerifiedPlan plan_and_verify(const Scenario& sc, const PlanRequest& request) {
  MissionOptions opt;
  opt.algorithm = request.algorithm;
  opt.seed = request.seed.value_or(sc.seed.value_or(1));
  opt.params = request.params;
  opt.stop = request.stop;
  if (request.time_limit_s > 0.0) opt.stop = opt.stop | StopCondition::time_limit(request.time_limit_s);
  opt.stop = opt.stop.with_threads(request.threads)
                 .with_memory_cap(request.max_memory_bytes.value_or(default_memory_cap_bytes()));
  opt.progress = request.progress;
  VerifiedPlan out;
  const auto t0 = std::chrono::steady_clock::now();
  out.plan = plan_mission(sc, opt);
  out.plan_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  out.violations = finalize_plan(sc, out.plan);
  return out;
}

}  // namespace uavplan
