#include "app/window/draw_pacer.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

using Clock = DrawPacer::Clock;
using std::chrono::milliseconds;

TEST(DrawPacer, DrawsKeepToAGridOfThePeriod) {
  DrawPacer pacer;
  EXPECT_NEAR(std::chrono::duration<double>(pacer.period()).count(), 1.0 / 60.0, 1e-9);
  pacer.setSoftware(true);
  const Clock::duration period = pacer.period();
  EXPECT_NEAR(std::chrono::duration<double>(period).count(), 1.0 / 30.0, 1e-9);
  const Clock::time_point t0 = Clock::now();
  pacer.drawStarts(t0);
  EXPECT_EQ(pacer.nextDraw(), t0 + period) << "the grid starts from the first draw";
  pacer.drawStarts(t0 + period + milliseconds(5));  // a late draw brings the next forward
  EXPECT_EQ(pacer.nextDraw(), t0 + 2 * period);
  pacer.drawStarts(t0 + 5 * period);  // more than a period late: the grid starts again
  EXPECT_EQ(pacer.nextDraw(), t0 + 6 * period);
}

TEST(DrawPacer, AWakeupSettlesOverTwoDrawsAndIsRecentForHalfASecond) {
  DrawPacer pacer;
  const Clock::time_point t0 = Clock::now();
  EXPECT_EQ(pacer.wakeups(), 0u);
  pacer.wake();
  EXPECT_EQ(pacer.wakeups(), 1u);
  EXPECT_FALSE(pacer.settling());
  pacer.woken(t0);
  EXPECT_TRUE(pacer.settling());
  pacer.drawnOneToSettle();
  EXPECT_TRUE(pacer.settling());
  pacer.drawnOneToSettle();
  EXPECT_FALSE(pacer.settling());
  pacer.drawnOneToSettle();
  EXPECT_FALSE(pacer.settling());
  EXPECT_TRUE(pacer.recentInput(t0 + milliseconds(499)));
  EXPECT_FALSE(pacer.recentInput(t0 + milliseconds(500)));
}

}  // namespace
}  // namespace galsculpt
