#include "app/window/window_meters.h"

#include <algorithm>
#include <cstdio>

namespace galsculpt {

namespace {
double msBetween(WindowMeters::Clock::time_point a, WindowMeters::Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
}  // namespace

void WindowMeters::frameStarts(bool playing) {
  frameInput_ = pendingInput_;
  pendingInput_.reset();
  if (playing && lastReadyAt_) runIdleMs_.add(msBetween(*lastReadyAt_, Clock::now()));
  lastReadyAt_.reset();
}

void WindowMeters::frameArrives(double msFrame, double msView, Clock::time_point readyAt,
                                bool playing) {
  simulationRate_.tick(Clock::now());
  ++runFrames_;
  runFrameMs_.add(msFrame);
  runViewMs_.add(msView);
  if (playing) lastReadyAt_ = readyAt;
}

void WindowMeters::drawn(double cpuMs, bool inStroke) {
  const Clock::time_point now = Clock::now();
  windowCpuMs_.add(cpuMs);
  runWindowCpuMs_.add(cpuMs);
  if (lastDraw_ != Clock::time_point{}) {
    const double ms = msBetween(lastDraw_, now);
    runWindowMs_.add(ms);
    if (inStroke && lastDrawInStroke_) {
      ++strokeIntervals_;
      strokeSeconds_ += ms / 1000.0;
    }
  }
  lastDrawInStroke_ = inStroke;
  lastDraw_ = now;
  windowRate_.tick(now);
  ++runDraws_;
  if (drawnInput_) {
    const double ms = msBetween(*drawnInput_, now);
    latencyMs_.add(ms);
    runLatencyMs_.add(ms);
  }
  drawnInput_.reset();
}

const WindowMeters::Overlay& WindowMeters::overlay() {
  const Clock::time_point now = Clock::now();
  if (now - overlay_.at > std::chrono::milliseconds(250)) {
    overlay_ = {now,
                windowRate_.rate(now),
                windowCpuMs_.median(),
                simulationRate_.rate(now),
                latencyMs_.empty() ? -1.0 : latencyMs_.median(),
                latencyMs_.empty() ? -1.0 : latencyMs_.last()};
  }
  return overlay_;
}

std::string WindowMeters::runSummary(int threads) const {
  const double seconds = std::chrono::duration<double>(Clock::now() - runStart_).count();
  char line[768];
  std::snprintf(line, sizeof line,
                "window: %d draws, %.1f a second, median %.1f ms between draws, %.2f ms of its "
                "thread a draw; simulation: %d frames, median %.1f ms a frame; input to screen: "
                "median %.0f ms over %zu samples; %d threads; between frames: median %.1f ms "
                "building the view, %.1f ms waiting for the window; during strokes: %.1f draws "
                "a second over %.1f s",
                runDraws_, runDraws_ / std::max(seconds, 1e-9), runWindowMs_.median(),
                runWindowCpuMs_.median(), runFrames_, runFrameMs_.median(), runLatencyMs_.median(),
                runLatencyMs_.size(), threads, runViewMs_.median(), runIdleMs_.median(),
                strokeIntervals_ / std::max(strokeSeconds_, 1e-9), strokeSeconds_);
  return line;
}

}  // namespace galsculpt
