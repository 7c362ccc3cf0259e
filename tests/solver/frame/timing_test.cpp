#include "solver/frame/timing.h"

#include <gtest/gtest.h>

#include <thread>

namespace galsculpt {
namespace {

TEST(Timing, MillisecondsSinceAMomentOnTheSteadyClock) {
  const auto start = Clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double ms = msSince(start);
  EXPECT_GE(ms, 20.0);
  EXPECT_LT(ms, 20000.0);
  EXPECT_TRUE(Clock::is_steady);
}

}  // namespace
}  // namespace galsculpt
