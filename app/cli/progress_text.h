// What the long commands (run, play, bench, mesh import) say of their progress on a terminal.
#pragma once

#include <string>

namespace galsculpt {

// Seconds as "42 s" or "3 min 05 s".
std::string durationText(double seconds);

// "42 s elapsed, ~1 min 10 s left": the time since the start and, while work is left, an
// estimate of the time left at the mean pace so far (`done` of `total` units in `elapsedS`).
std::string paceText(int done, int total, double elapsedS);

}  // namespace galsculpt
