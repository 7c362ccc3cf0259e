#include "app/cli/progress_text.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace galsculpt {

std::string durationText(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  std::ostringstream t;
  if (s < 60) {
    t << s << " s";
  } else {
    t << s / 60 << " min " << std::setw(2) << std::setfill('0') << s % 60 << " s";
  }
  return t.str();
}

std::string paceText(int done, int total, double elapsedS) {
  std::string text = durationText(elapsedS) + " elapsed";
  if (done < total && done > 0)
    text += ", ~" + durationText(elapsedS / done * (total - done)) + " left";
  return text;
}

}  // namespace galsculpt
