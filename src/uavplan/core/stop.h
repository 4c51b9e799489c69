// Composable stop conditions: a time limit, an iteration cap and cancel flags; a combination
// stops as soon as any part does (OMPL's termination conditions, as a value type).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

namespace uavplan {

class StopCondition {
 public:
  using Clock = std::chrono::steady_clock;

  StopCondition() = default;  // never stops
  static StopCondition time_limit(double seconds);
  static StopCondition iterations(std::uint64_t max_iterations);
  // The flag must outlive every copy of the condition.
  static StopCondition cancel_flag(const std::atomic<bool>* flag);

  // Stops when either stops.
  StopCondition operator|(const StopCondition& other) const;

  // True when planning must end; `iteration` is the caller's count of its main loop.
  bool should_stop(std::uint64_t iteration = 0) const;
  bool has_time_limit() const { return deadline_.has_value(); }

 private:
  std::optional<Clock::time_point> deadline_;
  std::optional<std::uint64_t> max_iterations_;
  std::vector<const std::atomic<bool>*> cancel_flags_;
};

}  // namespace uavplan
