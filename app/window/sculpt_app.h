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
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "app/render/renderer.h"
#include "app/window/app_command.h"
#include "app/window/camera.h"
#include "app/window/frame_view.h"
#include "app/window/input_script.h"
#include "app/window/partial_redraw.h"
#include "app/window/rate_meter.h"
#include "app/window/sculpt_window.h"
#include "app/window/simulation_worker.h"
#include "app/window/sub_buffer_present.h"
#include "app/window/tool_controller.h"
#include "engine/scene/scene_edit.h"
#include "engine/session/recovery.h"
#include "engine/session/session_loader.h"
#include "engine/surface/surface_bvh.h"

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
    ++wakeups_;
    presentAll_ = true;
  }
  // On a software rasterizer the window draws at most 30 times a second instead of 60.
  void setSoftwareRenderer(bool software) { softwareRenderer_ = software; }

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
  void show(FrameView view);
  void betweenFrames();
  void waitForWork();
  bool wantsSteadyDraws() const;
  bool frameShouldStart() const;
  void afterSwap(double cpuMsAtStart);
  std::optional<std::vector<PixelRect>> drawScreen(int width, int height);
  void checkPresent(int width, int height);
  std::optional<RayHit> hoverShown();
  void autosave();
  void takeScreenshot(int width, int height);
  void fail(const std::string& message);
  void report(const std::string& message);
  bool busy() const { return opener_.busy(); }
  bool stepInFlight() const { return frames_.inFlight(); }
  bool navigationOnly(const InputEvent& e) const;
  Clock::duration drawPeriod() const;  // 1/60 s, or 1/30 s on a software rasterizer
  // Input queued, acted on but not drawn, or riding in the frame in flight.
  bool inputNotYetShown() const;
  bool restyled() const;  // the drawn view's colours are not the chosen ones
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
  bool playing_ = true;
  bool stepOnce_ = false;
  bool applySettings_ = false;  // the Scene panel's Apply, done between frames
  FrameView shown_;             // what is on the screen, and what the overlay reports
  SurfaceBvh shownBvh_;         // over shown_.surface, for the brush cursor
  std::uint64_t bvhDamage_ = ~0ull, bvhGeneration_ = ~0ull;
  int bvhFaces_ = -1;
  double cursorX_ = 0.0, cursorY_ = 0.0;        // the newest cursor sample (window pixels)
  std::vector<std::pair<float, float>> trail_;  // a knife stroke's samples so far
  bool trailing_ = false;

  // Pacing and the overlay's live figures.
  std::size_t wakeups_ = 0;  // input events and redraw requests so far
  Clock::time_point nextDraw_{}, lastDraw_{}, lastInput_{};
  int redraw_ = 0;  // frames still to draw after an event (ImGui settles over a few)
  bool softwareRenderer_ = false;
  // Partial redraws on a software rasterizer (GALSCULPT_FULL_REDRAWS=1 turns them off, to
  // compare): the parts that changed are drawn and shown, the back buffer never swapped.
  bool partialRedraws_ = std::getenv("GALSCULPT_FULL_REDRAWS") == nullptr;
  std::unique_ptr<SubBufferPresent> present_;
  bool checkPresent_ = std::getenv("GALSCULPT_CHECK_PRESENT") != nullptr;
  int presentChecks_ = 0;
  long presentDiffering_ = 0;
  bool presentAll_ = true;
  PanelRedraws panelRedraws_;
  int drawnWidth_ = 0, drawnHeight_ = 0;
  RateMeter windowRate_, simulationRate_;
  struct OverlayRates {  // what the overlay shows of the rates, refreshed 4 times a second
    Clock::time_point at{};
    double windowFps = 0.0, windowCpuMs = 0.0, simulationFps = 0.0;
    double latencyMedianMs = -1.0, latencyLastMs = -1.0;
  } overlayRates_;
  RecentMedian latencyMs_, windowCpuMs_, windowMs_;
  // The same over the whole run, for the line the window logs when it closes (benchmarks).
  RecentMedian runLatencyMs_{1u << 20}, runWindowCpuMs_{1u << 20}, runWindowMs_{1u << 20},
      runFrameMs_{1u << 20}, runViewMs_{1u << 20}, runIdleMs_{1u << 20};
  // When the last frame played was ready: the time until the next one starts is the
  // simulation's wait for the window.
  std::optional<Clock::time_point> lastReadyAt_;
  int runDraws_ = 0, runFrames_ = 0;
  // Draws while a stroke is held, the rate a user sees while sculpting: the intervals between
  // two draws that both fell within a stroke, and their time.
  int strokeIntervals_ = 0;
  double strokeSeconds_ = 0.0;
  bool lastDrawInStroke_ = false;
  Clock::time_point runStart_ = Clock::now();
  // The earliest input that acted on the session and is not yet on the screen: waiting for a
  // frame to start, in the frame in flight, and in the view drawn this window frame.
  std::optional<Clock::time_point> pendingInput_, frameInput_, drawnInput_;
  int viewsShown_ = 0;  // views of finished frames drawn (scripts' "wait_frames")

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
  int scriptWaitViews_ = -1;  // "wait_frames": wait until viewsShown_ reaches it
  bool scripted_ = false;
  bool realtime_ = false;  // a script that lets frames run on the worker as a user would
  std::string pendingScreenshot_;
};

}  // namespace galsculpt
