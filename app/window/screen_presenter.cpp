#include "app/window/screen_presenter.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <utility>

#include "app/render/gl.h"
#include "app/render/offscreen_context.h"

namespace galsculpt {

void ScreenPresenter::init(GLFWwindow* window, bool software) {
  if (software && partialRedraws_) {
    present_ = std::make_unique<SubBufferPresent>(window);
    if (!present_->supported()) present_.reset();
  }
}

std::optional<std::vector<PixelRect>> ScreenPresenter::draw(Renderer& renderer,
                                                            const OrbitCamera& camera,
                                                            const RenderOptions& options, int width,
                                                            int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  ImDrawData* ui = ImGui::GetDrawData();
  PixelRect sceneChanged;
  if (!renderer.cached()) {
    renderer.draw(camera, width, height, options);
    ImGui_ImplOpenGL3_RenderDrawData(ui);
    return std::nullopt;
  }
  if (!renderer.update(camera, width, height, options, &sceneChanged)) {
    ImGui_ImplOpenGL3_RenderDrawData(ui);  // drawn straight to the screen: no cache here
    return std::nullopt;
  }
  // Everything is drawn and shown after a resize or an expose, and without partial presents.
  const bool full = !present_ || showAll_ || width != drawnWidth_ || height != drawnHeight_;
  showAll_ = false;
  drawnWidth_ = width;
  drawnHeight_ = height;
  RedrawPlan plan = panelRedraws_.plan(*ui, sceneChanged, width, height, full);
  renderer.present(plan.restore);
  DrawDataSubset subset(*ui, plan.lists);
  ImGui_ImplOpenGL3_RenderDrawData(subset.get());
  if (!present_) return std::nullopt;
  return std::move(plan.restore);
}

void ScreenPresenter::present(GLFWwindow* window,
                              const std::optional<std::vector<PixelRect>>& changed, int width,
                              int height) {
  if (!changed) {
    glfwSwapBuffers(window);
    return;
  }
  present_->present(*changed);
  if (check_) checkPresent(width, height);
}

std::vector<std::uint8_t> ScreenPresenter::readBackBuffer(int width, int height) {
  std::vector<std::uint8_t> pixels(static_cast<size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  return pixels;
}

std::optional<std::string> ScreenPresenter::writeScreenshot(int width, int height) {
  if (screenshot_.empty()) return std::nullopt;
  const std::string path = std::exchange(screenshot_, {});
  writePng(path, width, height, topRowFirst(readBackBuffer(width, height), width, height));
  return path;
}

// What the window shows (its front buffer, read back from the X server by Mesa's software
// rasterizer) against the whole back buffer, the picture it should show: a partial present that
// left a stale part would differ.
void ScreenPresenter::checkPresent(int width, int height) {
  const size_t size = static_cast<size_t>(width) * height * 4;
  const std::vector<std::uint8_t> back = readBackBuffer(width, height);
  const std::vector<std::uint8_t> screen = present_->readScreen(width, height);
  long differing = screen.size() == size ? 0 : width * static_cast<long>(height);
  for (size_t i = 0; screen.size() == size && i < size; i += 4) {
    if (back[i] != screen[i] || back[i + 1] != screen[i + 1] || back[i + 2] != screen[i + 2])
      ++differing;
  }
  ++checks_;
  differing_ += differing;
}

std::string ScreenPresenter::checkSummary() const {
  if (!check_) return {};
  return "present check: " + std::to_string(checks_) + " partial draws, " +
         std::to_string(differing_) + " pixels on the screen unlike the picture";
}

}  // namespace galsculpt
