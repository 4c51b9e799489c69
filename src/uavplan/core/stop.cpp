#include "uavplan/core/stop.h"
#include "uavplan/core/text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <thread>

namespace uavplan {

StopCondition StopCondition::time_limit(double seconds, Clock::time_point since) {
  // A limit past 1e9 s (31 years) is no limit in practice, and beyond about 9.2e9 s the clock's
  // nanoseconds would overflow into the past: such limits are held at 1e9 s.
  constexpr double kLongest_s = 1e9;
  StopCondition c;
  const double s = std::isnan(seconds) ? 0.0 : std::clamp(seconds, 0.0, kLongest_s);
  c.deadline_ = since + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
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
    c.max_iterations_ =
        c.max_iterations_ ? std::min(*c.max_iterations_, *other.max_iterations_) : *other.max_iterations_;
  c.cancel_flags_.insert(c.cancel_flags_.end(), other.cancel_flags_.begin(), other.cancel_flags_.end());
  if (other.threads_ > 0) c.threads_ = c.threads_ > 0 ? std::min(c.threads_, other.threads_) : other.threads_;
  if (other.memory_cap_bytes_ > 0)
    c.memory_cap_bytes_ =
        c.memory_cap_bytes_ > 0 ? std::min(c.memory_cap_bytes_, other.memory_cap_bytes_) : other.memory_cap_bytes_;
  return c;
}

double StopCondition::seconds_left() const {
  if (!deadline_) return std::numeric_limits<double>::infinity();
  return std::chrono::duration<double>(*deadline_ - Clock::now()).count();
}

StopCondition StopCondition::with_threads(int threads) const {
  StopCondition c = *this;
  c.threads_ = std::max(0, threads);
  return c;
}

StopCondition StopCondition::with_memory_cap(std::uint64_t bytes) const {
  StopCondition c = *this;
  c.memory_cap_bytes_ = bytes;
  return c;
}

int StopCondition::threads(int most) const {
  const int n = threads_ > 0 ? threads_ : static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(n, 1, std::max(1, most));
}

void StopCondition::require_memory(std::uint64_t bytes, const std::string& what) const {
  if (memory_cap_bytes_ == 0 || bytes <= memory_cap_bytes_) return;
  const std::string buf = strf(" needs %.4g MiB, above the memory cap of %.4g MiB (--max-memory)", bytes / 1048576.0,
                               memory_cap_bytes_ / 1048576.0);
  throw std::invalid_argument(what + buf);
}

bool StopCondition::should_stop(std::uint64_t iteration) const {
  if (max_iterations_ && iteration >= *max_iterations_) return true;
  for (const auto* f : cancel_flags_)
    if (f->load(std::memory_order_relaxed)) return true;
  if (deadline_ && Clock::now() >= *deadline_) return true;
  return false;
}

}  // namespace uavplan
