// A plan for a whole scenario: per UAV a route and a time-stamped trajectory.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "uavplan/core/status.h"
#include "uavplan/planning/problem.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {

// One UAV's outcome (reason: why it is not solved; the message says it in words) and flight.
struct UavPlan : Outcome {
  std::string id;
  std::vector<Vec3> waypoints;
  Trajectory trajectory;
  // Two lengths: the distance flown (the trajectory's polyline, as metrics.length_m, the CLI
  // table, the report and results.csv show it; set with the metrics), and the planned route's
  // (the waypoints' polyline; longer or shorter where the flight cuts or widens its corners).
  double length_m = 0.0;
  double route_length_m = 0.0;
  double arrival_s = 0.0;
  PlanStats stats;
  std::map<std::string, double> metrics;  // filled by evaluation
};

// A formation's flight (P1): one ETA, the phases' ends, and when each UAV left its slot (flag w).
struct FormationLog {
  struct Phase {
    std::string name;
    double end_s = 0.0;
  };
  struct Break {
    std::string uav;
    double from_s = 0.0, to_s = 0.0;
  };
  double eta_s = 0.0;
  // The farthest any UAV was from its slot at a period's start while the shape was held (none:
  // the mission does not keep a schedule).
  std::optional<double> worst_slot_error_m;
  // formation: the spread of the UAVs' arrivals (each at its goal to stay), against
  // mission.arrival_tolerance_s.
  std::optional<double> arrival_spread_s;
  std::vector<Phase> phases;
  std::vector<Break> breaks;
};

// The whole plan's outcome: combined_status of its UAVs, the first unsolved UAV's reason.
struct Plan : Outcome {
  std::string scenario;
  std::string algorithm;
  std::uint64_t seed = 0;
  std::vector<UavPlan> uavs;
  std::map<std::string, double> metrics;  // filled by evaluation
  double plan_ms = 0.0;                   // wall time; kept out of the plan file by default
  std::vector<std::string> notes;         // for the user, not the file (parameters ignored, ...)
  std::optional<FormationLog> formation;  // formation missions

  const UavPlan* find_uav(std::string_view id) const {
    for (const auto& u : uavs)
      if (u.id == id) return &u;
    return nullptr;
  }
};

// solved when every UAV is, failed when none is, partial otherwise.
Status combined_status(const std::vector<UavPlan>& uavs);
// The plan's outcome from its UAVs': combined_status, the first unsolved UAV's reason, and its
// message (prefixed with its id) where the plan has none yet.
void combine_outcomes(Plan& plan);

}  // namespace uavplan
