// The window's ImGui parts: the menu, the tools panel, the scene settings, the overlay, the
// tool's cursor and the dialogs (loading, errors, crash recovery, a file command's path). They
// read the window's state through a PanelContext and act through commands (app_command.h), the
// same ones keys and scripts give; what they hold themselves is what only they show: messages,
// the dialogs' state, the Scene panel's values being edited, the cursor and the knife's trail.
#pragma once

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/window/app_command.h"
#include "app/window/camera.h"
#include "app/window/frame_view.h"
#include "app/window/simulation_worker.h"
#include "app/window/tool_controller.h"
#include "app/window/window_meters.h"
#include "engine/scene/scene_edit.h"
#include "engine/session/recovery.h"
#include "engine/surface/surface_bvh.h"

namespace galsculpt {

// What the panels read and may change of the window's state, for one draw.
struct PanelContext {
  GLFWwindow* window = nullptr;
  SculptSession* session = nullptr;            // null until a file is open
  const ToolController* controller = nullptr;  // likewise
  ToolSettings& tools;
  SurfaceStyle& style;
  bool& wireframe;
  bool playing = false;
  bool scripted = false;   // scripted input: panels never take the mouse, errors close at once
  const FrameView& shown;  // what is on the screen, and what the overlay reports
  const OrbitCamera& camera;
  WindowMeters& meters;
  const OpenWorker& opener;
  const RecoveryStore& recovery;
  const std::filesystem::path& currentFile;
  const std::filesystem::path& projectFile;
  std::function<void(const Command&)> execute;
};

class WindowPanels {
 public:
  void draw(PanelContext& c);

  // A line under the overlay's figures, and an error shown in a dialog.
  void setStatus(std::string message) { status_ = std::move(message); }
  void showError(std::string message) {
    error_ = std::move(message);
    showError_ = true;
  }
  // A file command without a path: the path dialog asks for one.
  void askPath(AppCommand command) { askingPath_ = command; }
  // Autosaved sessions of processes that ended without closing: offered for recovery.
  void offerRecovery(std::vector<std::filesystem::path> files) {
    recoverable_ = std::move(files);
    askRecovery_ = !recoverable_.empty();
  }

  // The Scene panel's values (restarting the simulation applies them), and whether its Apply
  // was pressed since the last call (applied between frames).
  SceneSettings& editing() { return editing_; }
  bool takeApply() { return std::exchange(apply_, false); }

  // The newest cursor sample (window pixels), and the knife stroke's samples while one is drawn.
  void cursorAt(double x, double y);
  void knifeStroke(bool drawing);

 private:
  void drawMenu(PanelContext& c);
  void drawToolsPanel(PanelContext& c);
  void drawOverlay(PanelContext& c);
  void drawScenePanel(PanelContext& c);
  void drawCursor(PanelContext& c);
  std::optional<RayHit> hoverShown(const PanelContext& c, int width, int height);
  void drawDialogs(PanelContext& c);
  void drawRecoveryDialog(PanelContext& c);
  void drawPathDialog(PanelContext& c);

  std::string status_, error_;
  bool showError_ = false;
  std::optional<AppCommand> askingPath_;  // the command the path dialog is for
  char path_[1024] = {};
  std::vector<std::filesystem::path> recoverable_;
  bool askRecovery_ = false;
  SceneSettings editing_;
  bool apply_ = false;
  double cursorX_ = 0.0, cursorY_ = 0.0;
  std::vector<std::pair<float, float>> trail_;  // a knife stroke's samples so far
  bool trailing_ = false;
  SurfacePicker shownPicker_;  // over the shown surface, for the brush cursor
};

}  // namespace galsculpt
