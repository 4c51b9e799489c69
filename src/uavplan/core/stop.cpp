#include "uavplan/core/stop.h"

#include <algorithm>

namespace uavplan {

StopCondition StopCondition::time_limit(double seconds) {
  StopCondition c;
  c.deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(std::max(0.0, seconds)));
  return c;
}

StopCondition StopCondition::iterations(std::uint64_t max_iterations) {
  StopCondition c;
  c.max_iterations_ = max_iterations;
  return c;
}

StopCondition StopCondition::cancel_flag(const std::atomic<bool>* flag) {
  StopCondition c;
  if (flag) c.cancel_flags_.push_back(flag);
  return c;
}

StopCondition StopCondition::operator|(const StopCondition& other) const {
  StopCondition c = *this;
  if (other.deadline_) c.deadline_ = c.deadline_ ? std::min(*c.deadline_, *other.deadline_) : *other.deadline_;
  if (other.max_iterations_)
    c.max_iterations_ = c.max_iterations_ ? std::min(*c.max_iterations_, *other.max_iterations_)
                                          : *other.max_iterations_;
  c.cancel_flags_.insert(c.cancel_flags_.end(), other.cancel_flags_.begin(), other.cancel_flags_.end());
  return c;
}

bool StopCondition::should_stop(std::uint64_t iteration) const {
  if (max_iterations_ && iteration >= *max_iterations_) return true;
  for (const auto* f : cancel_flags_)
    if (f->load(std::memory_order_relaxed)) return true;
  if (deadline_ && Clock::now() >= *deadline_) return true;
  return false;
}

}  // namespace uavplan
