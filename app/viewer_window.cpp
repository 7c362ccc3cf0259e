// The interactive window: GLFW + Dear ImGui over the shared renderer.
//
// Navigation: left drag orbits, right or middle drag (or shift + left) pans, the wheel zooms,
// F frames the object, 1 / 3 / 7 give the front, side and top views (as in Blender).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/camera.h"
#include "app/gl.h"
#include "app/render_mesh.h"
#include "app/renderer.h"
#include "app/view_content.h"

namespace galsculpt {

namespace {

struct WindowState {
  OrbitCamera camera;
  BoundingBox box;
  double lastX = 0.0, lastY = 0.0;
  bool wireframe = false;
};

void handleInput(GLFWwindow* window, WindowState& s) {
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  const double dx = x - s.lastX, dy = y - s.lastY;
  s.lastX = x;
  s.lastY = y;
  if (io.WantCaptureMouse) return;
  int width = 1, height = 1;
  glfwGetWindowSize(window, &width, &height);
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                     glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
  if (left && !shift) s.camera.orbit(-dx * 0.01, dy * 0.01);
  if (right || (left && shift)) s.camera.pan(dx / height, dy / height);
  if (io.MouseWheel != 0.0f) s.camera.zoom(std::pow(0.9, io.MouseWheel));
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
      glfwSetWindowShouldClose(window, 1);
    if (ImGui::IsKeyPressed('F')) s.camera.frame(s.box);
    if (ImGui::IsKeyPressed('1')) s.camera.viewFront();
    if (ImGui::IsKeyPressed('3')) s.camera.viewSide();
    if (ImGui::IsKeyPressed('7')) s.camera.viewTop();
    if (ImGui::IsKeyPressed('W')) s.wireframe = !s.wireframe;
  }
}

void drawOverlay(const ViewContent& content, WindowState& s) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::Begin("Galsculpt", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::TextUnformatted(content.title.c_str());
  for (const std::string& fact : content.facts) ImGui::TextUnformatted(fact.c_str());
  ImGui::Separator();
  ImGui::Text("%.1f fps", static_cast<double>(ImGui::GetIO().Framerate));
  if (ImGui::Button("Front (1)")) s.camera.viewFront();
  ImGui::SameLine();
  if (ImGui::Button("Side (3)")) s.camera.viewSide();
  ImGui::SameLine();
  if (ImGui::Button("Top (7)")) s.camera.viewTop();
  ImGui::SameLine();
  if (ImGui::Button("Frame (F)")) s.camera.frame(s.box);
  ImGui::Checkbox("Wireframe (W)", &s.wireframe);
  ImGui::TextDisabled("left drag: orbit, right drag: pan, wheel: zoom");
  ImGui::End();
}

}  // namespace

bool runViewerWindow(const ViewContent& content, std::string* error) {
  if (!glfwInit()) {
    if (error) *error = "GLFW could not initialise";
    return false;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  const std::string title = "Galsculpt - " + content.title;
  GLFWwindow* window = glfwCreateWindow(1280, 800, title.c_str(), nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    if (error) *error = "no OpenGL 3.3 core window";
    return false;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");

  bool ok = true;
  {
    Renderer renderer;
    if (!renderer.init(error)) {
      ok = false;
    } else {
      renderer.setMesh(makeRenderMesh(content.surface, Vec3(0.80, 0.55, 0.42)));
      WindowState state;
      state.box = boundingBox(content.surface.vertices);
      state.camera.frame(state.box);
      glfwGetCursorPos(window, &state.lastX, &state.lastY);
      while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        handleInput(window, state);
        drawOverlay(content, state);
        ImGui::Render();
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        renderer.draw(state.camera, width, height, RenderOptions{state.wireframe});
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        glfwSwapBuffers(window);
      }
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return ok;
}

}  // namespace galsculpt
