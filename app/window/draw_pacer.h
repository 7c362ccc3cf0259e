// When the window draws: at 60 Hz (30 on a software rasterizer), on a grid of the period, while
// something moves on it, and otherwise only when something arrives. It counts the wakeups
// (input events, redraw requests) and lets ImGui settle its hover and layout over two draws
// after each.
#pragma once

#include <chrono>
#include <cstddef>

namespace galsculpt {

class DrawPacer {
 public:
  using Clock = std::chrono::steady_clock;

  void setSoftware(bool software) { software_ = software; }
  bool software() const { return software_; }
  Clock::duration period() const {
    const double hz = software_ ? 30.0 : 60.0;
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / hz));
  }
  // A draw starts now. Draws keep to a grid of the period: a late one brings the next forward,
  // so the rate holds (one more than a period late, the grid starts again from now).
  void drawStarts(Clock::time_point now) {
    nextDraw_ = (now - nextDraw_ > period() ? now : nextDraw_) + period();
  }
  Clock::time_point nextDraw() const { return nextDraw_; }

  void wake() { ++wakeups_; }
  std::size_t wakeups() const { return wakeups_; }
  // A wait ended by a wakeup: input is recent, and the next two draws let ImGui settle.
  void woken(Clock::time_point now) {
    lastInput_ = now;
    settle_ = 2;
  }
  bool settling() const { return settle_ > 0; }
  void drawnOneToSettle() {
    if (settle_ > 0) --settle_;
  }
  bool recentInput(Clock::time_point now) const {
    return now - lastInput_ < std::chrono::milliseconds(500);
  }

 private:
  bool software_ = false;
  std::size_t wakeups_ = 0;
  Clock::time_point nextDraw_{}, lastInput_{};
  int settle_ = 0;  // draws still to come after a wakeup
};

}  // namespace galsculpt
