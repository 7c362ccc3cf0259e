#include "app/window/sub_buffer_present.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

// GLFW's X11 and GLX accessors, declared here as glfw3native.h declares them: that header
// would pull in the X11 extension headers (Xrandr) for two functions.
extern "C" {
struct _XDisplay;
_XDisplay* glfwGetX11Display(void);
unsigned long glfwGetGLXWindow(GLFWwindow* window);
}

namespace galsculpt {

SubBufferPresent::SubBufferPresent(GLFWwindow* window) : window_(window) {
  // The context must be current; an X11 window with a GLX context (not EGL, not Wayland).
  if (glfwExtensionSupported("GLX_MESA_copy_sub_buffer") != GLFW_TRUE) return;
  display_ = glfwGetX11Display();
  drawable_ = glfwGetGLXWindow(window);
  if (!display_ || !drawable_) return;
  copy_ = reinterpret_cast<CopySubBuffer>(glfwGetProcAddress("glXCopySubBufferMESA"));
}

void SubBufferPresent::present(const std::vector<PixelRect>& parts) const {
  for (const PixelRect& p : parts)
    if (!p.empty()) copy_(display_, drawable_, p.x0, p.y0, p.x1 - p.x0, p.y1 - p.y0);
}

}  // namespace galsculpt
