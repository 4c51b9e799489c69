// Composable stop conditions: a time limit, an iteration cap and cancel flags; a combination
// stops as soon as any part does (OMPL's termination conditions, as a value type). It also carries
// what a run may use, so that every planner it reaches reads the same: the threads (0 = every
// core) and the memory a planner may allocate for its grids and graphs (0 = no cap).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace uavplan {

// Thrown by set-up code (a cell map, a grid, a roadmap being built) when the stop condition
// holds, so that a long set-up ends within the limit too; Planner::plan and plan_mission turn it
// into a result stopped with Reason::stopped. Not a std::exception: nothing else catches it.
struct Stopped {};

class StopCondition {
 public:
  using Clock = std::chrono::steady_clock;

  StopCondition() = default;  // never stops
  // `seconds` after `since` (a command's limit counts from its process's start).
  static StopCondition time_limit(double seconds, Clock::time_point since = Clock::now());
  static StopCondition iterations(std::uint64_t max_iterations);
  // The flag must outlive every copy of the condition.
  static StopCondition cancel_flag(const std::atomic<bool>* flag);

  // Stops when either stops.
  StopCondition operator|(const StopCondition& other) const;

  // True when planning must end; `iteration` is the caller's count of its main loop.
  bool should_stop(std::uint64_t iteration = 0) const;
  // Throws Stopped when should_stop().
  void throw_if_stopped() const {
    if (should_stop()) throw Stopped{};
  }
  bool has_time_limit() const { return deadline_.has_value(); }
  // Seconds left before the deadline (+inf without one).
  double seconds_left() const;

  StopCondition with_threads(int threads) const;
  StopCondition with_memory_cap(std::uint64_t bytes) const;
  // Threads to use: the set count, else the hardware's (at least 1), never above `most`.
  int threads(int most = 1 << 20) const;
  std::uint64_t memory_cap_bytes() const { return memory_cap_bytes_; }
  // Throws std::invalid_argument naming `what` when `bytes` exceed the memory cap.
  void require_memory(std::uint64_t bytes, const std::string& what) const;

 private:
  std::optional<Clock::time_point> deadline_;
  std::optional<std::uint64_t> max_iterations_;
  std::vector<const std::atomic<bool>*> cancel_flags_;
  int threads_ = 0;
  std::uint64_t memory_cap_bytes_ = 0;
};

}  // namespace uavplan
