// The one way a scenario is planned and verified: the command line's `plan`, the Python module's
// plan() and every run of a batch call plan_and_verify, so the same request gives the same plan,
// the same verdict and the same limits everywhere.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"
#include "uavplan/coordination/contract/violation.h"
#include "uavplan/core/stop.h"
#include "uavplan/planning/params.h"

namespace uavplan {

// Half the machine's memory: the cap of a planner's grids where none is asked for; 0 where the
// machine does not say.
std::uint64_t default_memory_cap_bytes();

// A batch run's cap where none is asked for: default_memory_cap_bytes() shared by the runs that
// go at once (`jobs`; 0: every core).
std::uint64_t default_run_memory_cap_bytes(int jobs);

struct PlanRequest {
  std::optional<std::string> algorithm;  // else the scenario's planner, else the mission's default
  std::optional<std::uint64_t> seed;     // else the scenario's seed, else 1
  Params params;                         // merged over the scenario's planner.params
  double time_limit_s = 0.0;             // counted from the call; 0: none
  StopCondition stop;                    // more reasons to stop (an interrupt, a deadline of the caller)
  int threads = 0;                       // threads the planners may use; 0: every core
  // Memory a planner's grids may take; nullopt: default_memory_cap_bytes(); 0: no cap.
  std::optional<std::uint64_t> max_memory_bytes;
  std::function<void(std::size_t done, std::size_t total)> progress;  // UAVs planned (may be empty)
};

struct VerifiedPlan {
  Plan plan;                          // finalized: a UAV the verifier faults is not solved
  std::vector<Violation> violations;  // what the verifier found in what was planned
  double plan_ms = 0.0;               // planning alone (wall time)
};

// Plans the scenario's mission and verifies the plan (finalize_plan). A stop that comes while
// planning leaves the UAVs not planned `stopped`; the plan is verified all the same. Throws
// std::invalid_argument for a planner that cannot plan the mission or a bad parameter.
VerifiedPlan plan_and_verify(const Scenario& scenario, const PlanRequest& request);

}  // namespace uavplan
