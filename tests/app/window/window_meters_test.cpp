#include "app/window/window_meters.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

using Clock = WindowMeters::Clock;
using std::chrono::milliseconds;

// Input that acted rides in the next frame and counts from its arrival to the draw that shows
// its view; input that acted between frames counts to the next draw.
TEST(WindowMeters, LatencyRunsFromInputToTheDrawThatShowsIt) {
  WindowMeters meters;
  EXPECT_FALSE(meters.inputWaiting());
  meters.inputActs(Clock::now() - milliseconds(80));
  meters.inputActs(Clock::now() - milliseconds(10));  // the earliest counts
  EXPECT_TRUE(meters.inputWaiting());
  meters.frameStarts(true);
  EXPECT_TRUE(meters.inputWaiting()) << "riding in the frame in flight";
  meters.frameArrives(12.0, 3.0, Clock::now(), true);
  EXPECT_EQ(meters.framesArrived(), 1);
  meters.frameShown();
  EXPECT_FALSE(meters.inputWaiting());
  meters.drawn(1.5, false);
  const WindowMeters::Overlay& first = meters.overlay();
  EXPECT_GE(first.latencyLastMs, 80.0);
  EXPECT_LT(first.latencyLastMs, 80.0 + 60'000.0);

  meters.inputActs(Clock::now() - milliseconds(200));
  meters.actedBetweenFramesShown();
  meters.drawn(1.5, false);
  const std::string line = meters.runSummary(2);
  EXPECT_NE(line.find("window: 2 draws"), std::string::npos) << line;
  EXPECT_NE(line.find("simulation: 1 frames, median 12.0 ms a frame"), std::string::npos) << line;
  EXPECT_NE(line.find("over 2 samples; 2 threads"), std::string::npos) << line;
  EXPECT_NE(line.find("median 3.0 ms building the view"), std::string::npos) << line;
}

// A dropped frame's input is not waited for; draws within a stroke count toward its rate.
TEST(WindowMeters, DroppedFramesAndStrokes) {
  WindowMeters meters;
  meters.inputActs(Clock::now());
  meters.frameStarts(false);
  meters.frameDropped();
  EXPECT_FALSE(meters.inputWaiting());
  meters.drawn(1.0, true);
  meters.drawn(1.0, true);
  meters.drawn(1.0, false);
  const std::string line = meters.runSummary(1);
  EXPECT_EQ(line.find("during strokes: 0.0 draws"), std::string::npos) << line;
  EXPECT_NE(line.find("over 0 samples"), std::string::npos) << "no input reached the screen";
}

}  // namespace
}  // namespace galsculpt
