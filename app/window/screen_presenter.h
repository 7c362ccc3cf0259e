// How a drawn window frame reaches the screen. Normally: everything drawn into the back buffer
// and swapped. On a software rasterizer, with the scene cached (renderer.h), only what changed
// is drawn again (partial_redraw.h) and copied to the window from a back buffer that is never
// swapped (sub_buffer_present.h); GALSCULPT_FULL_REDRAWS=1 turns that off, to compare, and
// GALSCULPT_CHECK_PRESENT=1 compares the screen with the picture after each partial present
// (the UI tests use it).
#pragma once

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render/renderer.h"
#include "app/window/camera.h"
#include "app/window/partial_redraw.h"
#include "app/window/sub_buffer_present.h"

namespace galsculpt {

class ScreenPresenter {
 public:
  // `software`: a software rasterizer draws the window (partial presents where it can).
  void init(GLFWwindow* window, bool software);
  // The next draw draws and shows everything (a resize, an expose, a refresh).
  void showAllNext() { showAll_ = true; }
  // The scene and ImGui's draw data into the back buffer; returns the parts to copy to the
  // screen for a partial present, or nullopt for a swap.
  std::optional<std::vector<PixelRect>> draw(Renderer& renderer, const OrbitCamera& camera,
                                             const RenderOptions& options, int width, int height);
  // Shows what draw drew: the parts it returned copied to the window, or a swap.
  void present(GLFWwindow* window, const std::optional<std::vector<PixelRect>>& changed, int width,
               int height);
  // The next draw is written to `path` as a PNG once drawn, panels included.
  void screenshotNext(std::string path) { screenshot_ = std::move(path); }
  bool screenshotPending() const { return !screenshot_.empty(); }
  // Writes the screenshot asked for, if any, from the back buffer; returns its path. Throws
  // OutputError when it cannot be written (the request is dropped either way).
  std::optional<std::string> writeScreenshot(int width, int height);
  // The back buffer's pixels (RGBA, bottom row first).
  static std::vector<std::uint8_t> readBackBuffer(int width, int height);
  // The present check's line for the log, or empty when it was not asked for.
  std::string checkSummary() const;

 private:
  void checkPresent(int width, int height);
  bool partialRedraws_ = std::getenv("GALSCULPT_FULL_REDRAWS") == nullptr;
  bool check_ = std::getenv("GALSCULPT_CHECK_PRESENT") != nullptr;
  std::unique_ptr<SubBufferPresent> present_;
  int checks_ = 0;
  long differing_ = 0;
  bool showAll_ = true;
  PanelRedraws panelRedraws_;
  int drawnWidth_ = 0, drawnHeight_ = 0;
  std::string screenshot_;
};

}  // namespace galsculpt
