// Outcome of planning: expected results are a status and a reason, misuse is an exception.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace uavplan {

enum class Status { solved, partial, failed };

constexpr std::string_view to_string(Status s) {
  switch (s) {
    case Status::solved:
      return "solved";
    case Status::partial:
      return "partial";
    case Status::failed:
      return "failed";
  }
  return "failed";
}

// Why a result is what it is, as a value (OMPL's PlannerStatus is the model): what callers, the
// batch's status column and the plan file branch on. The message says it in words for people;
// nothing reads an outcome from a message.
enum class Reason {
  none,      // solved, or nothing more to say
  stopped,   // the stop condition (a time limit, an interrupt) ended planning first
  budget,    // the planner's own budget ran out (max_nodes, max_expansions, iterations, memory)
  no_route,  // the search ended without a route (none exists, or none at this resolution)
  invalid,   // the problem cannot be posed (no goal, a start the mission cannot use)
  conflict,  // the other UAVs or the moving obstacles leave it no way (separation, departure)
  rejected,  // the verifier found a violation in what was planned
};

constexpr std::string_view to_string(Reason r) {
  switch (r) {
    case Reason::none:
      return "none";
    case Reason::stopped:
      return "stopped";
    case Reason::budget:
      return "budget";
    case Reason::no_route:
      return "no_route";
    case Reason::invalid:
      return "invalid";
    case Reason::conflict:
      return "conflict";
    case Reason::rejected:
      return "rejected";
  }
  return "none";
}

inline std::optional<Reason> reason_from_string(std::string_view s) {
  for (Reason r : {Reason::none, Reason::stopped, Reason::budget, Reason::no_route, Reason::invalid, Reason::conflict,
                   Reason::rejected})
    if (to_string(r) == s) return r;
  return std::nullopt;
}

inline std::optional<Status> status_from_string(std::string_view s) {
  if (s == "solved") return Status::solved;
  if (s == "partial") return Status::partial;
  if (s == "failed") return Status::failed;
  return std::nullopt;
}

// How a result ended, the one shape every result type has (planners, searches, MAPF, RRT,
// landings, the batch's runs): a result type derives from it and adds its own data. `message`
// says it in words for people; callers branch on `status` and `reason`.
struct Outcome {
  Status status = Status::failed;
  Reason reason = Reason::none;
  std::string message;

  bool solved() const { return status == Status::solved; }
  void succeed() {
    status = Status::solved;
    reason = Reason::none;
  }
  void fail(Reason why, std::string words = {}) {
    status = Status::failed;
    reason = why;
    message = std::move(words);
  }
};

}  // namespace uavplan
