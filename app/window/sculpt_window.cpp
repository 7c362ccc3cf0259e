#include "app/window/sculpt_window.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/window/sculpt_app.h"

#include <cstring>

#include "app/render/gl.h"

namespace galsculpt {

namespace {

SculptApp* appOf(GLFWwindow* w) {
  return static_cast<SculptApp*>(glfwGetWindowUserPointer(w));
}

void onCursor(GLFWwindow* w, double x, double y) {
  InputEvent e;
  e.kind = InputEvent::Kind::Move;
  e.x = x;
  e.y = y;
  appOf(w)->enqueue(e);
}

void onButton(GLFWwindow* w, int button, int action, int mods) {
  InputEvent e;
  e.kind = InputEvent::Kind::Button;
  e.button = button == GLFW_MOUSE_BUTTON_RIGHT    ? MouseButton::Right
             : button == GLFW_MOUSE_BUTTON_MIDDLE ? MouseButton::Middle
                                                  : MouseButton::Left;
  e.pressed = action == GLFW_PRESS;
  e.shift = mods & GLFW_MOD_SHIFT;
  e.ctrl = mods & GLFW_MOD_CONTROL;
  appOf(w)->enqueue(e);
}

void onScroll(GLFWwindow* w, double, double dy) {
  InputEvent e;
  e.kind = InputEvent::Kind::Scroll;
  e.y = dy;
  appOf(w)->enqueue(e);
}

void onKey(GLFWwindow* w, int key, int, int action, int mods) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  // GLFW's codes are ASCII for letters, digits, space, '.', '[' and ']'.
  e.key = key == GLFW_KEY_ESCAPE ? kKeyEscape : key;
  e.shift = mods & GLFW_MOD_SHIFT;
  e.ctrl = mods & GLFW_MOD_CONTROL;
  appOf(w)->enqueue(e);
}

void onRefresh(GLFWwindow* w) {
  appOf(w)->requestRedraw();
}

void onResize(GLFWwindow* w, int, int) {
  appOf(w)->requestRedraw();
}

// Whether OpenGL here is a software rasterizer: asked of a hidden window's context, before the
// real window's framebuffer (multisampled or not) is chosen.
bool softwareRenderer() {
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  GLFWwindow* probe = glfwCreateWindow(16, 16, "", nullptr, nullptr);
  glfwWindowHint(GLFW_VISIBLE, GLFW_TRUE);
  if (!probe) return false;
  glfwMakeContextCurrent(probe);
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  bool software = false;
  for (const char* name : {"llvmpipe", "softpipe", "Software Rasterizer", "SWR"})
    software = software || (renderer && std::strstr(renderer, name));
  glfwMakeContextCurrent(nullptr);
  glfwDestroyWindow(probe);
  return software;
}

}  // namespace

bool runSculptWindow(const SculptWindowOptions& options, std::ostream& log, std::string* error) {
  // A bad input script is an error before any window opens.
  if (options.inputScript) loadInputScript(*options.inputScript);
  if (!glfwInit()) {
    if (error) *error = "GLFW could not initialise";
    return false;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // On a software rasterizer (llvmpipe under Xvfb or without a GPU driver) a drawn frame costs
  // the CPU the simulation runs on: no multisampling there (it quadruples the pixels' work),
  // and the window draws at most 30 times a second (sculpt_app.cpp).
  const bool software = softwareRenderer();
  glfwWindowHint(GLFW_SAMPLES, software ? 0 : 4);
  GLFWwindow* window =
      glfwCreateWindow(options.width, options.height, "Galsculpt", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    if (error) *error = "no OpenGL 3.3 core window";
    return false;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.inputScript ? 0 : 1);

  bool ok = true;
  {
    SculptApp app(window, options, log);
    app.setSoftwareRenderer(software);
    glfwSetWindowUserPointer(window, &app);
    // Ours first: ImGui's backend chains to callbacks installed before it.
    glfwSetCursorPosCallback(window, onCursor);
    glfwSetMouseButtonCallback(window, onButton);
    glfwSetScrollCallback(window, onScroll);
    glfwSetKeyCallback(window, onKey);
    glfwSetWindowRefreshCallback(window, onRefresh);
    glfwSetFramebufferSizeCallback(window, onResize);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330");
    if (app.init(error)) {
      app.run();
    } else {
      ok = false;
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return ok;
}

}  // namespace galsculpt
