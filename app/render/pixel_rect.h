// A rectangle of framebuffer pixels, OpenGL's way up (row 0 at the bottom), half-open:
// [x0, x1) x [y0, y1). Partial redraws are planned in these.
#pragma once

#include <algorithm>

namespace galsculpt {

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x1 <= x0 || y1 <= y0; }
  long area() const { return empty() ? 0 : static_cast<long>(x1 - x0) * (y1 - y0); }
  bool intersects(const PixelRect& o) const {
    return !empty() && !o.empty() && x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
  // The smallest rectangle holding both (an empty one adds nothing).
  PixelRect united(const PixelRect& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
  }
  PixelRect clipped(int width, int height) const {
    PixelRect r{std::max(x0, 0), std::max(y0, 0), std::min(x1, width), std::min(y1, height)};
    return r.empty() ? PixelRect{} : r;
  }
  PixelRect grown(int pixels) const {
    return empty() ? *this : PixelRect{x0 - pixels, y0 - pixels, x1 + pixels, y1 + pixels};
  }
  bool operator==(const PixelRect&) const = default;
};

}  // namespace galsculpt
