// Events a second over the last moments (the overlay's window and simulation rates), and the
// median of the last few durations (its input latency). Times are passed in, so tests can
// drive them.
#pragma once

#include <algorithm>
#include <chrono>
#include <deque>
#include <vector>

namespace galsculpt {

class RateMeter {
 public:
  using Time = std::chrono::steady_clock::time_point;
  explicit RateMeter(double spanSeconds = 2.0) : span_(spanSeconds) {}

  void tick(Time at) {
    ticks_.push_back(at);
    while (ticks_.size() > 2 && seconds(ticks_.front(), at) > span_) ticks_.pop_front();
  }
  // Ticks a second over the span ending now; 0 when the last tick is older than the span.
  double rate(Time now) const {
    if (ticks_.size() < 2 || seconds(ticks_.back(), now) > span_) return 0.0;
    const double elapsed = seconds(ticks_.front(), ticks_.back());
    return elapsed > 0.0 ? static_cast<double>(ticks_.size() - 1) / elapsed : 0.0;
  }

 private:
  static double seconds(Time a, Time b) { return std::chrono::duration<double>(b - a).count(); }
  double span_;
  std::deque<Time> ticks_;
};

// The median of the last `keep` samples (0 with none).
class RecentMedian {
 public:
  explicit RecentMedian(size_t keep = 15) : keep_(keep) {}
  void add(double v) {
    samples_.push_back(v);
    if (samples_.size() > keep_) samples_.pop_front();
  }
  bool empty() const { return samples_.empty(); }
  size_t size() const { return samples_.size(); }
  double last() const { return samples_.empty() ? 0.0 : samples_.back(); }
  double median() const {
    if (samples_.empty()) return 0.0;
    std::vector<double> s(samples_.begin(), samples_.end());
    std::nth_element(s.begin(), s.begin() + static_cast<long>(s.size() / 2), s.end());
    return s[s.size() / 2];
  }

 private:
  size_t keep_;
  std::deque<double> samples_;
};

}  // namespace galsculpt
