// The sculpting window's application object (internal to app/window): its state, and where its
// parts live. sculpt_app.cpp: the frame loop, input, scripted input, loading, autosave.
// app_command_dispatch.cpp: the one dispatcher of typed commands (app_command.h) that menus,
// keys, panels and scripts share. panels.cpp: the ImGui menu, panels, overlay, cursor and
// dialogs. simulation_worker.h: the threads that run simulation frames and open files.
// sculpt_window.cpp: GLFW callbacks and the window's lifetime.
#pragma once

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "app/render/renderer.h"
#include "app/window/app_command.h"
#include "app/window/camera.h"
#include "app/window/input_script.h"
#include "app/window/sculpt_window.h"
#include "app/window/simulation_worker.h"
#include "app/window/tool_controller.h"
#include "engine/scene/scene_edit.h"
#include "engine/session/recovery.h"
#include "engine/session/session_loader.h"

namespace galsculpt {

// One input event, from GLFW or from an input script.
struct InputEvent {
  enum class Kind { Move, Button, Scroll, Key };
  Kind kind = Kind::Move;
  double x = 0.0, y = 0.0;  // Move: window pixels; Scroll: y steps
  MouseButton button = MouseButton::Left;
  bool pressed = false, shift = false, ctrl = false;
  int key = 0;
};

class SculptApp {
 public:
  SculptApp(GLFWwindow* window, const SculptWindowOptions& options, std::ostream& log)
      : window_(window), options_(options), log_(log) {}

  bool init(std::string* error);
  void run();
  std::vector<InputEvent>& queue() { return queue_; }

 private:
  using Clock = std::chrono::steady_clock;

  // sculpt_app.cpp
  void startLoading(const std::filesystem::path& file);
  void finishLoading();
  void adopt(OpenedSession opened, const std::filesystem::path& file);
  void processInput();
  void handleEvent(const InputEvent& e);
  void runScriptStep();
  void advanceSimulation();
  void updateScene();
  void autosave();
  void takeScreenshot(int width, int height);
  void fail(const std::string& message);
  void report(const std::string& message);
  bool busy() const { return opener_.busy(); }
  bool stepInFlight() const { return frames_.inFlight(); }
  bool navigationOnly(const InputEvent& e) const;
  void finishStep();
  void collectStep();
  void finish();

  // app_command_dispatch.cpp
  void execute(const Command& command);
  bool applyAtOnce(const Command& command);
  bool applyToTools(const Command& command);
  void applyToSession(const Command& command);
  void applySceneSettings();
  void frameHoveredPiece();

  // panels.cpp
  void drawUi();
  void drawMenu();
  void drawToolsPanel();
  void drawOverlay();
  void drawScenePanel();
  void drawDialogs();
  void drawRecoveryDialog();
  void drawPathDialog();
  void drawCursor();

  GLFWwindow* window_;
  SculptWindowOptions options_;
  std::ostream& log_;
  Renderer renderer_;
  OrbitCamera camera_;
  std::unique_ptr<SculptSession> session_;
  std::unique_ptr<ToolController> controller_;
  ToolSettings toolSettings_;
  std::filesystem::path currentFile_, projectFile_;
  std::vector<InputEvent> queue_;

  // Background work: opening files, simulation frames.
  OpenWorker opener_;
  FrameWorker frames_;

  // View.
  SurfaceStyle style_;
  bool wireframe_ = false;
  SceneSettings editing_;  // the Scene panel's values, applied by restarting the simulation
  char grid_[64] = {};
  bool playing_ = true;
  bool stepOnce_ = false;
  std::uint64_t shownGeneration_ = ~0ull, shownDamage_ = ~0ull;
  SurfaceStyle shownStyle_;
  std::vector<int> anchored_;

  // Overlay figures.
  FrameMetrics metrics_;
  std::string backendName_;         // as of the last finished frame
  std::vector<std::string> notes_;  // the simulation's notes, as of the last finished frame
  double msSurface_ = 0.0;

  // Dialogs and messages.
  std::optional<AppCommand> askingPath_;  // the command the path dialog is for
  char path_[1024] = {};
  std::string error_, status_;
  bool showError_ = false;
  std::vector<std::filesystem::path> recoverable_;
  bool askRecovery_ = false;

  // Autosave.
  std::unique_ptr<RecoveryStore> recovery_;
  Clock::time_point lastAutosave_ = Clock::now();

  // Scripted input.
  std::vector<InputStep> script_;
  size_t scriptNext_ = 0;
  int scriptWait_ = 0;
  bool scripted_ = false;
  bool realtime_ = false;  // a script that lets frames run on the worker as a user would
  std::string pendingScreenshot_;
};

}  // namespace galsculpt
