// The sculpting window's application object (internal to app/window): the frame loop, input and
// the session, and where its other parts live. sculpt_app.cpp: the loop, input, scripted input,
// loading, autosave. app_command_dispatch.cpp: the one dispatcher of typed commands
// (app_command.h) that menus, keys, panels and scripts share. window_panels.h: the ImGui menu,
// panels, overlay, cursor and dialogs. window_meters.h: rates and latencies. draw_pacer.h: when
// to draw. screen_presenter.h: how a draw reaches the screen. simulation_worker.h: the threads
// that run simulation frames and open files. sculpt_window.cpp: GLFW callbacks and the window's
// lifetime.
#pragma once

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "app/render/renderer.h"
#include "app/window/app_command.h"
#include "app/window/camera.h"
#include "app/window/draw_pacer.h"
#include "app/window/frame_view.h"
#include "app/window/input_script.h"
#include "app/window/screen_presenter.h"
#include "app/window/sculpt_window.h"
#include "app/window/simulation_worker.h"
#include "app/window/tool_controller.h"
#include "app/window/window_meters.h"
#include "app/window/window_panels.h"
#include "engine/session/recovery.h"
#include "engine/session/session_loader.h"

namespace galsculpt {

// One input event, from GLFW or from an input script, or a command from a menu or a panel that
// must wait for the frame in flight (queued with the input, so that everything acts in order).
struct InputEvent {
  enum class Kind { Move, Button, Scroll, Key, Command };
  Kind kind = Kind::Move;
  double x = 0.0, y = 0.0;  // Move: window pixels; Scroll: y steps
  MouseButton button = MouseButton::Left;
  bool pressed = false, shift = false, ctrl = false;
  int key = 0;
  Command command{AppCommand::Play, ""};
  std::chrono::steady_clock::time_point at{};  // when it arrived (set by enqueue)
};

class SculptApp {
 public:
  SculptApp(GLFWwindow* window, const SculptWindowOptions& options, std::ostream& log)
      : window_(window), options_(options), log_(log) {}

  bool init(std::string* error);
  void run();
  // An event as it arrives (GLFW's callbacks, scripted input): the cursor and the knife's trail
  // follow it at once; what it does waits its turn (processInput).
  void enqueue(InputEvent e);
  // Something other than input needs the window drawn (it was resized or exposed).
  // An expose or a refresh: the next draw also shows everything again.
  void requestRedraw() {
    pacer_.wake();
    presenter_.showAllNext();
  }
  // On a software rasterizer the window draws at most 30 times a second instead of 60.
  void setSoftwareRenderer(bool software) { pacer_.setSoftware(software); }

 private:
  using Clock = std::chrono::steady_clock;

  // sculpt_app.cpp
  void finishLoading();
  void adopt(OpenedSession opened, const std::filesystem::path& file);
  void processInput();
  void handleEvent(const InputEvent& e);
  void runScriptStep();
  void advanceSimulation();
  void updateScene();
  void show(FrameView view);
  void betweenFrames();
  void waitForWork();
  bool wantsSteadyDraws() const;
  bool frameShouldStart() const;
  void drawUi();
  void autosave();
  void fail(const std::string& message);
  void report(const std::string& message);
  bool busy() const { return opener_.busy(); }
  bool stepInFlight() const { return frames_.inFlight(); }
  bool navigationOnly(const InputEvent& e) const;
  // Input queued, acted on but not drawn, or riding in the frame in flight.
  bool inputNotYetShown() const;
  bool restyled() const;  // the drawn view's colours are not the chosen ones
  void finishStep();
  void finish();

  // app_command_dispatch.cpp
  void execute(const Command& command);
  bool applyAtOnce(const Command& command);
  bool applyToTools(const Command& command);
  void applyToSession(const Command& command);
  void applySceneSettings();
  void frameHoveredPiece();

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
  bool playing_ = true;
  bool stepOnce_ = false;
  FrameView shown_;  // what is on the screen, and what the overlay reports

  WindowPanels panels_;
  WindowMeters meters_;
  DrawPacer pacer_;
  ScreenPresenter presenter_;

  // Autosave.
  std::unique_ptr<RecoveryStore> recovery_;
  Clock::time_point lastAutosave_ = Clock::now();

  InputScriptRunner script_;
};

}  // namespace galsculpt
