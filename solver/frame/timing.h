// Milliseconds since a moment, for the per-phase figures every frame reports (StepReport, the
// metrics CSV, the overlay): one clock everywhere.
#pragma once

#include <chrono>

namespace galsculpt {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace galsculpt
