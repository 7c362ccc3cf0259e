#include "app/window/sub_buffer_present.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

// GLFW's X11 and GLX accessors, declared here as glfw3native.h declares them: that header
// would pull in the X11 extension headers (Xrandr) for three functions.
extern "C" {
Display* glfwGetX11Display(void);
Window glfwGetX11Window(GLFWwindow* window);
unsigned long glfwGetGLXWindow(GLFWwindow* window);
}

namespace {

int shiftOf(unsigned long mask) {
  int shift = 0;
  while (mask != 0 && (mask & 1ul) == 0) mask >>= 1, ++shift;
  return shift;
}

}  // namespace

namespace galsculpt {

SubBufferPresent::SubBufferPresent(GLFWwindow* window) : window_(window) {
  // The context must be current; an X11 window with a GLX context (not EGL, not Wayland).
  if (glfwExtensionSupported("GLX_MESA_copy_sub_buffer") != GLFW_TRUE) return;
  display_ = glfwGetX11Display();
  drawable_ = glfwGetGLXWindow(window);
  if (!display_ || !drawable_) return;
  copy_ = reinterpret_cast<CopySubBuffer>(glfwGetProcAddress("glXCopySubBufferMESA"));
}

std::vector<std::uint8_t> SubBufferPresent::readScreen(int width, int height) const {
  Display* display = static_cast<Display*>(display_);
  XSync(display, False);
  XImage* image = XGetImage(display, glfwGetX11Window(window_), 0, 0, static_cast<unsigned>(width),
                            static_cast<unsigned>(height), AllPlanes, ZPixmap);
  if (!image) return {};
  const int rs = shiftOf(image->red_mask), gs = shiftOf(image->green_mask),
            bs = shiftOf(image->blue_mask);
  std::vector<std::uint8_t> rgba(static_cast<size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y) {
    std::uint8_t* row = &rgba[static_cast<size_t>(height - 1 - y) * width * 4];
    for (int x = 0; x < width; ++x) {
      const unsigned long p = XGetPixel(image, x, y);
      row[4 * x] = static_cast<std::uint8_t>((p & image->red_mask) >> rs);
      row[4 * x + 1] = static_cast<std::uint8_t>((p & image->green_mask) >> gs);
      row[4 * x + 2] = static_cast<std::uint8_t>((p & image->blue_mask) >> bs);
      row[4 * x + 3] = 255;
    }
  }
  XDestroyImage(image);
  return rgba;
}

void SubBufferPresent::present(const std::vector<PixelRect>& parts) const {
  for (const PixelRect& p : parts)
    if (!p.empty()) copy_(display_, drawable_, p.x0, p.y0, p.x1 - p.x0, p.y1 - p.y0);
}

}  // namespace galsculpt
