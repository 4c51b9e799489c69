#include "uavplan/core/stop.h"

#include <gtest/gtest.h>

#include <thread>

namespace uavplan {
namespace {

TEST(StopCondition, DefaultNeverStops) { EXPECT_FALSE(StopCondition().should_stop(1'000'000'000)); }

TEST(StopCondition, IterationCap) {
  const auto c = StopCondition::iterations(10);
  EXPECT_FALSE(c.should_stop(9));
  EXPECT_TRUE(c.should_stop(10));
}

TEST(StopCondition, TimeLimitExpires) {
  const auto c = StopCondition::time_limit(0.01);
  EXPECT_FALSE(c.should_stop());
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_TRUE(c.should_stop());
}

TEST(StopCondition, CancelFlagAndComposition) {
  std::atomic<bool> cancel{false};
  const auto c = StopCondition::time_limit(100.0) | StopCondition::cancel_flag(&cancel) | StopCondition::iterations(50);
  EXPECT_FALSE(c.should_stop(1));
  EXPECT_TRUE(c.should_stop(50));
  cancel = true;
  EXPECT_TRUE(c.should_stop(1));
}

}  // namespace
}  // namespace uavplan
