#include "app/window/rate_meter.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

using std::chrono::milliseconds;

TEST(RateMeter, TicksASecondOverItsSpanAndNoneWhenStale) {
  RateMeter meter(2.0);
  const RateMeter::Time t0{};
  EXPECT_EQ(meter.rate(t0), 0.0);
  for (int k = 0; k <= 100; ++k) meter.tick(t0 + milliseconds(40 * k));  // 25 a second
  EXPECT_NEAR(meter.rate(t0 + milliseconds(4000)), 25.0, 1e-9);
  EXPECT_EQ(meter.rate(t0 + milliseconds(7000)), 0.0) << "nothing for longer than the span";
}

TEST(RecentMedian, KeepsTheLastSamples) {
  RecentMedian m(3);
  EXPECT_TRUE(m.empty());
  for (double v : {100.0, 1.0, 2.0, 3.0}) m.add(v);
  EXPECT_EQ(m.size(), 3u);
  EXPECT_EQ(m.median(), 2.0) << "the first sample fell out";
  EXPECT_EQ(m.last(), 3.0);
}

}  // namespace
}  // namespace galsculpt
