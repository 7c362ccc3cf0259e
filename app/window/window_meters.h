// The window's meters: how fast it draws and the simulation plays, and how long input takes to
// reach the screen (the overlay's live figures, refreshed four times a second), and the same
// over the whole run for the line the window logs when it closes (docs/benchmarks.md, "Threads
// and the window"). The window tells it what happens (input acting, a frame starting, a view
// drawn); it keeps the clocks.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "app/window/rate_meter.h"

namespace galsculpt {

class WindowMeters {
 public:
  using Clock = std::chrono::steady_clock;

  // Input that acts on the session arrived at `at` (the earliest not yet on the screen counts).
  void inputActs(Clock::time_point at) {
    if (!pendingInput_) pendingInput_ = at;
  }
  // A frame starts: the input waiting rides in it. `playing`: the time since the last frame
  // was ready is the simulation's wait for the window.
  void frameStarts(bool playing);
  // A frame's view arrived (`msFrame`, `msView`: what it cost, `readyAt`: when it was done).
  void frameArrives(double msFrame, double msView, Clock::time_point readyAt, bool playing);
  // The view of the frame in flight goes on the screen this draw.
  void frameShown() { showFrom(frameInput_); }
  // What acted between frames is on the screen from this draw.
  void actedBetweenFramesShown() { showFrom(pendingInput_); }
  // Views of finished frames arrived so far (what scripts' "wait_frames" counts in real time).
  int framesArrived() const { return runFrames_; }
  // The frame in flight was dropped (another session): its input is not waited for.
  void frameDropped() { frameInput_.reset(); }
  // Input that acted and is not yet on the screen (waiting for a frame or in the one in flight).
  bool inputWaiting() const { return pendingInput_ || frameInput_; }
  // A draw ended: `cpuMs` of the window's thread, `inStroke` while a stroke is held.
  void drawn(double cpuMs, bool inStroke);

  // The overlay's figures, read at most four times a second (figures that change at every draw
  // cannot be read, and would redraw the panel every time on a software rasterizer).
  struct Overlay {
    Clock::time_point at{};
    double windowFps = 0.0, windowCpuMs = 0.0, simulationFps = 0.0;
    double latencyMedianMs = -1.0, latencyLastMs = -1.0;
  };
  const Overlay& overlay();
  // The run's line for the log (threads: the solver's).
  std::string runSummary(int threads) const;

 private:
  void showFrom(std::optional<Clock::time_point>& input) {
    if (input && (!drawnInput_ || *input < *drawnInput_)) drawnInput_ = input;
    input.reset();
  }
  RateMeter windowRate_, simulationRate_;
  Overlay overlay_;
  RecentMedian latencyMs_, windowCpuMs_;
  // The same over the whole run.
  RecentMedian runLatencyMs_{1u << 20}, runWindowCpuMs_{1u << 20}, runWindowMs_{1u << 20},
      runFrameMs_{1u << 20}, runViewMs_{1u << 20}, runIdleMs_{1u << 20};
  // When the last frame played was ready: the time until the next one starts is the
  // simulation's wait for the window.
  std::optional<Clock::time_point> lastReadyAt_;
  int runDraws_ = 0, runFrames_ = 0;
  // Draws while a stroke is held, the rate a user sees while sculpting: the intervals between
  // two draws that both fell within a stroke, and their time.
  int strokeIntervals_ = 0;
  double strokeSeconds_ = 0.0;
  bool lastDrawInStroke_ = false;
  Clock::time_point runStart_ = Clock::now(), lastDraw_{};
  // The earliest input that acted on the session and is not yet on the screen: waiting for a
  // frame to start, in the frame in flight, and in the view drawn this window frame.
  std::optional<Clock::time_point> pendingInput_, frameInput_, drawnInput_;
};

}  // namespace galsculpt
