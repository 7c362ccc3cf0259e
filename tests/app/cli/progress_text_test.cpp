#include "app/cli/progress_text.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(ProgressText, DurationsReadAsSecondsThenMinutes) {
  EXPECT_EQ(durationText(0.4), "0 s");
  EXPECT_EQ(durationText(42.4), "42 s");
  EXPECT_EQ(durationText(59.6), "1 min 00 s");
  EXPECT_EQ(durationText(185.0), "3 min 05 s");
  EXPECT_EQ(durationText(-3.0), "0 s") << "a clock that stepped back reads as nothing";
}

TEST(ProgressText, TheTimeLeftIsTheWorkLeftAtTheMeanPaceSoFar) {
  EXPECT_EQ(paceText(1, 4, 10.0), "10 s elapsed, ~30 s left");
  EXPECT_EQ(paceText(3, 4, 90.0), "1 min 30 s elapsed, ~30 s left");
  EXPECT_EQ(paceText(4, 4, 40.0), "40 s elapsed") << "nothing left to estimate";
  EXPECT_EQ(paceText(0, 4, 2.0), "2 s elapsed") << "no pace yet";
}

}  // namespace
}  // namespace galsculpt
