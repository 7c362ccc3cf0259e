// Shows parts of the window's back buffer without swapping it (GLX_MESA_copy_sub_buffer, which
// Mesa's software rasterizer offers on X11). The back buffer then always holds the previous
// draw, so a draw need only redo what changed (partial_redraw.h), and only that is copied to
// the screen.
#pragma once

#include <cstdint>
#include <vector>

#include "app/render/pixel_rect.h"

struct GLFWwindow;

namespace galsculpt {

class SubBufferPresent {
 public:
  explicit SubBufferPresent(GLFWwindow* window);
  // Whether the window can be shown this way (else it swaps its buffers as usual).
  bool supported() const { return copy_ != nullptr; }
  // Copies the parts to the screen (each an implicit glFlush).
  void present(const std::vector<PixelRect>& parts) const;
  // What the X server shows in the window: RGBA rows from the bottom, as glReadPixels gives the
  // back buffer (empty when it cannot be read).
  std::vector<std::uint8_t> readScreen(int width, int height) const;

 private:
  using CopySubBuffer = void (*)(void* display, unsigned long drawable, int x, int y, int width,
                                 int height);
  GLFWwindow* window_;
  CopySubBuffer copy_ = nullptr;
  void* display_ = nullptr;
  unsigned long drawable_ = 0;
};

}  // namespace galsculpt
