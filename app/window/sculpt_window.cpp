#include "app/window/sculpt_window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <memory>
#include <mutex>
#include <thread>

#include "app/render/gl.h"
#include "app/render/offscreen_context.h"
#include "app/render/render_mesh.h"
#include "app/render/renderer.h"
#include "app/window/camera.h"
#include "app/window/input_script.h"
#include "app/window/tool_controller.h"
#include "engine/scene/scene_edit.h"
#include "engine/session/project_file.h"
#include "engine/session/recovery.h"
#include "engine/session/session_loader.h"
#include "engine/surface/surface_io.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

// One input event, from GLFW or from an input script.
struct InputEvent {
  enum class Kind { Move, Button, Scroll, Key };
  Kind kind = Kind::Move;
  double x = 0.0, y = 0.0;  // Move: window pixels; Scroll: y steps
  MouseButton button = MouseButton::Left;
  bool pressed = false, shift = false, ctrl = false;
  int key = 0;
};

enum class PathDialog { None, Open, SaveProject, SaveRecording, Export, ExportTets };

class SculptApp {
 public:
  SculptApp(GLFWwindow* window, const SculptWindowOptions& options, std::ostream& log)
      : window_(window), options_(options), log_(log) {}

  bool init(std::string* error);
  void run();
  std::vector<InputEvent>& queue() { return queue_; }

 private:
  // Loading happens on a worker thread so the window stays live (and shows progress).
  void startLoading(const fs::path& file);
  void finishLoading();
  void adopt(OpenedSession opened, const fs::path& file);
  void processInput();
  void handleEvent(const InputEvent& e);
  void handleKey(int key, bool ctrl, bool shift);
  void runScriptStep();
  void runCommand(const std::string& command, const std::string& argument);
  void advanceSimulation();
  void updateScene();
  void drawUi();
  void drawMenu();
  void drawToolsPanel();
  void drawOverlay();
  void drawScenePanel();
  void applySceneSettings();
  void frameHoveredPiece();
  void drawDialogs();
  void drawCursor();
  void autosave();
  void fail(const std::string& message);
  void report(const std::string& message);
  bool busy() const { return loading_.valid(); }
  bool stepInFlight() const { return stepping_.valid(); }
  bool navigationOnly(const InputEvent& e) const;
  void finishStep();
  void collectStep();
  void finish();

  GLFWwindow* window_;
  SculptWindowOptions options_;
  std::ostream& log_;
  Renderer renderer_;
  OrbitCamera camera_;
  std::unique_ptr<SculptSession> session_;
  std::unique_ptr<ToolController> controller_;
  ToolSettings toolSettings_;
  fs::path currentFile_, projectFile_;
  std::vector<InputEvent> queue_;

  // Loading.
  std::future<OpenedSession> loading_;
  fs::path loadingFile_;
  std::mutex progressMutex_;
  std::string progress_;

  // View.
  SurfaceStyle style_;
  bool wireframe_ = false;
  bool autoStressScale_ = true;
  SceneSettings editing_;  // the Scene panel's values, applied by restarting the simulation
  char grid_[64] = {};
  bool playing_ = true;
  bool stepOnce_ = false;
  std::uint64_t shownGeneration_ = ~0ull, shownDamage_ = ~0ull;
  SurfaceStyle shownStyle_;
  std::vector<int> anchored_;

  // The frame being computed on a worker thread, if any.
  std::future<FrameMetrics> stepping_;

  // Overlay figures.
  FrameMetrics metrics_;
  std::string backendName_;         // as of the last finished frame
  std::vector<std::string> notes_;  // the simulation's notes, as of the last finished frame
  double msSurface_ = 0.0;

  // Dialogs and messages.
  PathDialog dialog_ = PathDialog::None;
  char path_[1024] = {};
  std::string error_, status_;
  bool showError_ = false;
  std::vector<fs::path> recoverable_;
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
  void takeScreenshot(int width, int height);
};

void SculptApp::takeScreenshot(int width, int height) {
  if (pendingScreenshot_.empty()) return;
  std::vector<std::uint8_t> pixels(static_cast<size_t>(width) * height * 4), flipped(pixels.size());
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::memcpy(&flipped[y * row], &pixels[(height - 1 - y) * row], row);
  try {
    writePng(pendingScreenshot_, width, height, flipped);
    report("wrote " + pendingScreenshot_);
  } catch (const std::exception& e) {
    fail(e.what());
  }
  pendingScreenshot_.clear();
}

bool SculptApp::init(std::string* error) {
  if (!renderer_.init(error)) return false;
  playing_ = options_.startPlaying;
  recovery_ = std::make_unique<RecoveryStore>();
  if (options_.offerRecovery) {
    recoverable_ = recovery_->orphans();
    askRecovery_ = !recoverable_.empty();
  }
  if (options_.inputScript) {
    const InputScript script = loadInputScript(*options_.inputScript);
    script_ = script.steps;
    realtime_ = script.realtime;
    scripted_ = true;
  }
  startLoading(options_.file);
  return true;
}

void SculptApp::report(const std::string& message) {
  status_ = message;
  log_ << message << '\n';
}

void SculptApp::fail(const std::string& message) {
  error_ = message;
  showError_ = true;
  log_ << "error: " << message << '\n';
}

void SculptApp::startLoading(const fs::path& file) {
  if (busy()) return;
  loadingFile_ = file;
  {
    std::lock_guard<std::mutex> lock(progressMutex_);
    progress_ = "opening " + file.string();
  }
  loading_ = std::async(std::launch::async, [this, file] {
    return openSession(
        file,
        [this](const std::string& line) {
          std::lock_guard<std::mutex> lock(progressMutex_);
          progress_ = line;
        },
        20000, options_.backend);
  });
}

void SculptApp::finishLoading() {
  if (!busy() || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  finishStep();  // the old session's frame ends before the new session replaces it
  try {
    adopt(loading_.get(), loadingFile_);
  } catch (const std::exception& e) {
    // The current session (if any) stays; the user can open another file.
    loading_ = {};
    fail(std::string("cannot open ") + loadingFile_.string() + ":\n" + e.what());
  }
}

void SculptApp::adopt(OpenedSession opened, const fs::path& file) {
  if (controller_) controller_->cancelStroke();
  session_ = std::move(opened.session);
  controller_ = std::make_unique<ToolController>(*session_, camera_, toolSettings_);
  currentFile_ = file;
  projectFile_ = looksLikeProject(file) ? file : fs::path();
  camera_.frame(boundingBox(session_->simulation().state().x));
  if (opened.camera) camera_.setPose(*opened.camera);
  // A sensible brush for this object: a tenth of its size.
  const double size = boundingBox(session_->simulation().state().x).size().norm();
  toolSettings_.radius = 0.1 * size;
  toolSettings_.strength = 0.5 * size;
  shownGeneration_ = ~0ull;
  metrics_ = FrameMetrics{};
  editing_ = sceneSettings(session_->scene());
  std::snprintf(grid_, sizeof grid_, "%s", editing_.solver.grid.c_str());
  const std::string title = "Galsculpt - " + session_->scene().name;
  glfwSetWindowTitle(window_, title.c_str());
  report("opened " + file.string() + " (" +
         std::to_string(session_->simulation().model().numTets()) + " tets)");
}

void SculptApp::handleKey(int key, bool ctrl, bool shift) {
  if (!session_) return;
  if (ctrl) {
    switch (key) {
      case 'Z':
        controller_->cancelStroke();
        shift ? session_->redo() : session_->undo();
        break;
      case 'Y':
        controller_->cancelStroke();
        session_->redo();
        break;
      case 'S':
        if (!projectFile_.empty() && !shift)
          runCommand("save_project", projectFile_.string());
        else
          dialog_ = PathDialog::SaveProject;
        break;
      case 'O':
        dialog_ = PathDialog::Open;
        break;
      case 'E':
        dialog_ = PathDialog::Export;
        break;
      case 'Q':
        glfwSetWindowShouldClose(window_, 1);
        break;
    }
    return;
  }
  for (int t = 0; t < kToolCount; ++t) {
    if (key == toolKey(static_cast<Tool>(t)) && !controller_->strokeActive())
      toolSettings_.tool = static_cast<Tool>(t);
  }
  switch (key) {
    case ' ':
      playing_ = !playing_;
      break;
    case '.':
      stepOnce_ = true;
      break;
    case '[':
      (shift ? toolSettings_.strength : toolSettings_.radius) *= 0.8;
      break;
    case ']':
      (shift ? toolSettings_.strength : toolSettings_.radius) *= 1.25;
      break;
    case 'X':
      toolSettings_.symmetry = !toolSettings_.symmetry;
      break;
    case 'F':
      if (shift) {
        frameHoveredPiece();
      } else {
        camera_.frame(boundingBox(session_->simulation().state().x));
      }
      break;
    case '1':
      camera_.viewFront();
      break;
    case '3':
      camera_.viewSide();
      break;
    case '7':
      camera_.viewTop();
      break;
    case 'W':
      wireframe_ = !wireframe_;
      break;
    case 'V':
      style_.view = static_cast<SurfaceView>((static_cast<int>(style_.view) + 1) % 3);
      break;
    case 'C':
      style_.tintCracks = !style_.tintCracks;
      break;
  }
}

void SculptApp::handleEvent(const InputEvent& e) {
  const ImGuiIO& io = ImGui::GetIO();
  switch (e.kind) {
    case InputEvent::Kind::Move:
      if (controller_) controller_->mouseMove(e.x, e.y);
      break;
    case InputEvent::Kind::Button:
      // A press over a panel belongs to the panel; a release always ends what a press began.
      if (!controller_ || (e.pressed && io.WantCaptureMouse && !scripted_) || busy()) break;
      controller_->mouseButton(e.button, e.pressed, e.shift);
      break;
    case InputEvent::Kind::Scroll:
      if (controller_ && !(io.WantCaptureMouse && !scripted_)) controller_->scroll(e.y);
      break;
    case InputEvent::Kind::Key:
      if (!(io.WantCaptureKeyboard && !scripted_) && !busy()) handleKey(e.key, e.ctrl, e.shift);
      break;
  }
}

void SculptApp::runCommand(const std::string& command, const std::string& argument) {
  finishStep();  // commands act between frames
  try {
    if (command == "open") {
      startLoading(argument);
      return;
    }
    if (!session_) throw std::runtime_error("nothing is open");
    // A file holds whole actions: a stroke still held ends here.
    if (command == "save_project" || command == "save_recording") controller_->cancelStroke();
    if (command == "save_project") {
      writeProject(argument, *session_, camera_.pose());
      projectFile_ = argument;
      session_->markSaved();
      report("saved project " + argument);
    } else if (command == "save_recording") {
      session_->saveRecording(argument);
      report("saved recording " + argument + " (" + std::to_string(session_->recording().size()) +
             " events, " + std::to_string(session_->simulation().frame()) + " frames)");
    } else if (command == "export") {
      writeVisualSurface(argument, session_->simulation().surface());
      report("exported surface " + argument);
    } else if (command == "export_tets") {
      session_->simulation().writeTetsWithDamage(argument);
      report("exported tets " + argument + ".node/.ele/.face/.damage/.vtk");
    } else if (command == "undo") {
      controller_->cancelStroke();
      session_->undo();
    } else if (command == "redo") {
      controller_->cancelStroke();
      session_->redo();
    } else if (command == "reset") {
      controller_->cancelStroke();
      session_->reset();
    } else if (command == "play") {
      playing_ = true;
    } else if (command == "pause") {
      playing_ = false;
    } else if (command == "step") {
      stepOnce_ = true;
    } else if (command == "tool") {
      bool found = false;
      for (int t = 0; t < kToolCount; ++t) {
        if (argument == toolName(static_cast<Tool>(t))) {
          toolSettings_.tool = static_cast<Tool>(t);
          found = true;
        }
      }
      if (!found) throw std::runtime_error("unknown tool '" + argument + "'");
    } else if (command == "radius") {
      toolSettings_.radius = std::stod(argument);
    } else if (command == "strength") {
      toolSettings_.strength = std::stod(argument);
    } else if (command == "symmetry") {
      toolSettings_.symmetry = argument != "off";
      if (toolSettings_.symmetry)
        toolSettings_.symmetryAxis = argument == "y" ? 1 : argument == "z" ? 2 : 0;
    } else if (command == "preset") {  // as the Scene settings panel: edit, then apply
      editing_.material = materialPreset(argument);
      applySceneSettings();
    } else if (command == "grid") {
      std::snprintf(grid_, sizeof grid_, "%s", argument.c_str());
      applySceneSettings();
    } else if (command == "recover") {  // as the Recover button of the crash-recovery offer
      const std::vector<fs::path> orphans = recovery_->orphans();
      if (orphans.empty()) throw std::runtime_error("nothing to recover");
      startLoading(orphans.front());
    } else if (command == "frame_piece") {
      frameHoveredPiece();
    } else if (command == "screenshot") {
      pendingScreenshot_ = argument;  // taken once this frame is drawn, panels included
    } else if (command == "view") {
      style_.view = argument == "damage"   ? SurfaceView::Damage
                    : argument == "stress" ? SurfaceView::Stress
                                           : SurfaceView::Shaded;
    }
  } catch (const std::exception& e) {
    fail(command + " " + argument + ": " + e.what());
  }
}

void SculptApp::runScriptStep() {
  if (!scripted_ || busy()) return;
  if (scriptWait_ > 0) {
    --scriptWait_;
    return;
  }
  if (scriptNext_ >= script_.size()) {
    glfwSetWindowShouldClose(window_, 1);
    return;
  }
  const InputStep& s = script_[scriptNext_++];
  int width = 1, height = 1;
  glfwGetWindowSize(window_, &width, &height);
  InputEvent e;
  e.shift = s.shift;
  e.ctrl = s.ctrl;
  switch (s.kind) {
    case InputStep::Kind::Wait:
      scriptWait_ = s.frames;
      break;
    case InputStep::Kind::Move:
      e.kind = InputEvent::Kind::Move;
      for (const auto& [fx, fy] : s.points) {
        e.x = fx * width;
        e.y = fy * height;
        queue_.push_back(e);
      }
      break;
    case InputStep::Kind::Press:
    case InputStep::Kind::Release:
      e.kind = InputEvent::Kind::Button;
      e.button = s.button;
      e.pressed = s.kind == InputStep::Kind::Press;
      queue_.push_back(e);
      break;
    case InputStep::Kind::Scroll:
      e.kind = InputEvent::Kind::Scroll;
      e.y = s.scroll;
      queue_.push_back(e);
      break;
    case InputStep::Kind::Key:
      e.kind = InputEvent::Kind::Key;
      e.key = s.key;
      queue_.push_back(e);
      break;
    case InputStep::Kind::Command:
      runCommand(s.command, s.argument);
      break;
  }
}

bool SculptApp::navigationOnly(const InputEvent& e) const {
  switch (e.kind) {
    case InputEvent::Kind::Scroll:
      return true;
    case InputEvent::Kind::Move:
      return controller_->navigating();
    case InputEvent::Kind::Button:
      return e.pressed ? e.button != MouseButton::Left || toolSettings_.tool == Tool::Navigate
                       : controller_->navigating();
    case InputEvent::Kind::Key:
      return false;
  }
  return false;
}

void SculptApp::processInput() {
  std::vector<InputEvent> events;
  events.swap(queue_);
  size_t i = 0;
  // While a frame is being computed only navigation goes through; the first event that would
  // touch the session waits, with everything after it, for the frame to finish (so tools act
  // between frames, exactly as recorded).
  for (; i < events.size(); ++i) {
    if (stepInFlight() && (!controller_ || !navigationOnly(events[i]))) break;
    handleEvent(events[i]);
  }
  queue_.assign(events.begin() + static_cast<long>(i), events.end());
}

void SculptApp::finishStep() {
  if (stepping_.valid()) metrics_ = stepping_.get();
  // Read between frames: a frame in flight may change the backend (a device failure) and notes.
  if (session_) {
    backendName_ = session_->simulation().backendName();
    notes_ = session_->simulation().notes();
  }
}

void SculptApp::collectStep() {
  if (stepInFlight() && stepping_.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
    finishStep();
}

void SculptApp::advanceSimulation() {
  // Launch only: a finished frame is collected at the top of the loop, before input, so input
  // that waited for it goes through before the next frame starts.
  if (stepInFlight() || !session_ || busy()) return;
  session_->setCamera(camera_.pose());
  if (playing_ || stepOnce_) {
    stepOnce_ = false;
    // The frame runs on a worker thread: the window keeps drawing and navigating meanwhile.
    SculptSession* session = session_.get();
    stepping_ = std::async(std::launch::async, [session] { return session->step(); });
    if (scripted_ && !realtime_) finishStep();  // scripted input counts frames exactly
  }
}

void SculptApp::updateScene() {
  if (!session_ || stepInFlight()) return;  // the last frame's surface stays on screen
  const Simulation& sim = session_->simulation();
  const bool moved =
      sim.generation() != shownGeneration_ || sim.state().damageRevision != shownDamage_;
  const bool restyled = style_.view != shownStyle_.view ||
                        style_.tintCracks != shownStyle_.tintCracks ||
                        style_.scaleMax != shownStyle_.scaleMax;
  if (!moved && !restyled) return;
  SurfaceUpdateStats stats;
  const auto start = Clock::now();
  const VisualSurface& surface = sim.surface(&stats);
  msSurface_ = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  std::vector<double> values;
  if (style_.view == SurfaceView::Damage) {
    values = sim.vertexDamage();
    style_.scaleMax = 1.0;
  } else if (style_.view == SurfaceView::Stress) {
    values = sim.vertexStress();
    if (autoStressScale_) {
      // The hottest colour at the 98th percentile: a few peaks do not wash the rest out.
      std::vector<double> sorted = values;
      const size_t k = sorted.size() * 98 / 100;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
      style_.scaleMax = std::max(sorted[k], 1e-9);
    }
  }
  renderer_.setMesh(makeRenderMesh(surface, style_, values));
  anchored_ = sim.anchoredVertices();
  std::vector<Vec3> points;
  points.reserve(anchored_.size());
  for (int v : anchored_) points.push_back(sim.state().x[v]);
  renderer_.setPoints(points, kAnchorColor);
  shownGeneration_ = sim.generation();
  shownDamage_ = sim.state().damageRevision;
  shownStyle_ = style_;
}

void SculptApp::drawMenu() {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open...", "Ctrl+O")) dialog_ = PathDialog::Open;
    if (ImGui::MenuItem("Save project", "Ctrl+S", false, session_ != nullptr)) {
      if (projectFile_.empty())
        dialog_ = PathDialog::SaveProject;
      else
        runCommand("save_project", projectFile_.string());
    }
    if (ImGui::MenuItem("Save project as...", "Ctrl+Shift+S", false, session_ != nullptr))
      dialog_ = PathDialog::SaveProject;
    if (ImGui::MenuItem("Save recording...", nullptr, false, session_ != nullptr))
      dialog_ = PathDialog::SaveRecording;
    ImGui::Separator();
    if (ImGui::MenuItem("Export surface...", "Ctrl+E", false, session_ != nullptr))
      dialog_ = PathDialog::Export;
    if (ImGui::MenuItem("Export tet mesh...", nullptr, false, session_ != nullptr))
      dialog_ = PathDialog::ExportTets;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) glfwSetWindowShouldClose(window_, 1);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string undo =
        session_ && session_->canUndo() ? "Undo " + session_->undoLabel() : "Undo";
    const std::string redo =
        session_ && session_->canRedo() ? "Redo " + session_->redoLabel() : "Redo";
    if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, session_ && session_->canUndo()))
      runCommand("undo", "");
    if (ImGui::MenuItem(redo.c_str(), "Ctrl+Shift+Z", false, session_ && session_->canRedo()))
      runCommand("redo", "");
    if (ImGui::MenuItem("Reset to the start", nullptr, false, session_ != nullptr))
      runCommand("reset", "");
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Shaded", nullptr, style_.view == SurfaceView::Shaded))
      style_.view = SurfaceView::Shaded;
    if (ImGui::MenuItem("Damage", nullptr, style_.view == SurfaceView::Damage))
      style_.view = SurfaceView::Damage;
    if (ImGui::MenuItem("Stress", nullptr, style_.view == SurfaceView::Stress))
      style_.view = SurfaceView::Stress;
    ImGui::MenuItem("Wireframe", "W", &wireframe_);
    ImGui::MenuItem("Tint crack faces", "C", &style_.tintCracks);
    ImGui::Separator();
    if (ImGui::MenuItem("Frame", "F") && session_) {
      finishStep();
      camera_.frame(boundingBox(session_->simulation().state().x));
    }
    if (ImGui::MenuItem("Front", "1")) camera_.viewFront();
    if (ImGui::MenuItem("Side", "3")) camera_.viewSide();
    if (ImGui::MenuItem("Top", "7")) camera_.viewTop();
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void SculptApp::drawToolsPanel() {
  ImGui::SetNextWindowPos(ImVec2(10, 30), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tools", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  for (int t = 0; t < kToolCount; ++t) {
    const std::string label =
        std::string(toolName(static_cast<Tool>(t))) + " (" + toolKey(static_cast<Tool>(t)) + ")";
    if (ImGui::RadioButton(label.c_str(), toolSettings_.tool == static_cast<Tool>(t)))
      toolSettings_.tool = static_cast<Tool>(t);
  }
  ImGui::Separator();
  float radius = static_cast<float>(toolSettings_.radius);
  if (ImGui::SliderFloat("radius (m)", &radius, 1e-4f, 1.0f, "%.4f", ImGuiSliderFlags_Logarithmic))
    toolSettings_.radius = radius;
  float strength = static_cast<float>(toolSettings_.strength);
  if (ImGui::SliderFloat("strength (m/s)", &strength, 1e-4f, 10.0f, "%.4f",
                         ImGuiSliderFlags_Logarithmic))
    toolSettings_.strength = strength;
  ImGui::Checkbox("symmetry (X)", &toolSettings_.symmetry);
  if (toolSettings_.symmetry) {
    ImGui::SameLine();
    const char* axes[] = {"x", "y", "z"};
    ImGui::SetNextItemWidth(50);
    ImGui::Combo("plane", &toolSettings_.symmetryAxis, axes, 3);
    float offset = static_cast<float>(toolSettings_.symmetryOffset);
    if (ImGui::InputFloat("offset (m)", &offset)) toolSettings_.symmetryOffset = offset;
  }
  ImGui::Separator();
  if (ImGui::Button(playing_ ? "Pause (space)" : "Play (space)")) playing_ = !playing_;
  ImGui::SameLine();
  if (ImGui::Button("Step (.)")) stepOnce_ = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset")) runCommand("reset", "");
  const char* views[] = {"shaded", "damage", "stress"};
  int view = static_cast<int>(style_.view);
  if (ImGui::Combo("view (V)", &view, views, 3)) style_.view = static_cast<SurfaceView>(view);
  if (style_.view == SurfaceView::Stress) {
    float scale = static_cast<float>(style_.scaleMax);
    if (ImGui::SliderFloat("hottest (Pa)", &scale, 1.0f, 1e9f, "%.3g",
                           ImGuiSliderFlags_Logarithmic))
      style_.scaleMax = scale;
  }
  ImGui::Checkbox("wireframe (W)", &wireframe_);
  ImGui::SameLine();
  ImGui::Checkbox("tint cracks (C)", &style_.tintCracks);
  ImGui::TextDisabled("left: tool   right: orbit   middle: pan   wheel: zoom");
  ImGui::End();
}

// A combo box over the values of a settings enum, shown by their scene-file names.
template <typename E, size_t N>
void pickEnum(const char* label, E& value, const E (&values)[N], const char* (*nameOf)(E)) {
  const char* names[N];
  int current = 0;
  for (size_t k = 0; k < N; ++k) {
    names[k] = nameOf(values[k]);
    if (values[k] == value) current = static_cast<int>(k);
  }
  if (ImGui::Combo(label, &current, names, static_cast<int>(N))) value = values[current];
}

// Wrap width of the overlay's free text, in pixels (its figures' lines are about this wide).
constexpr float kOverlayTextWidth = 340.0f;

void SculptApp::drawOverlay() {
  // Pinned by its top-right corner to the screen's: as its figures widen it grows leftwards,
  // never off the edge.
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 10, 30), ImGuiCond_Always,
                          ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("Simulation", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  // Long lines (a scene's name, a backend fallback's reason) wrap instead of widening it.
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + kOverlayTextWidth);
  ImGui::Text("%.1f fps (window)", static_cast<double>(ImGui::GetIO().Framerate));
  if (session_) {
    const Simulation& sim = session_->simulation();
    const SceneDescription& scene = session_->scene();
    ImGui::Text("%s: %d vertices, %d tets", scene.name.c_str(), sim.model().numVertices(),
                sim.model().numTets());
    ImGui::Text("material: %s (%s)", scene.material.preset.c_str(),
                materialModelName(scene.material.model));
    ImGui::Text("solver: %s %s on the %s backend", solverTypeName(scene.solver.type),
                scene.solver.grid.c_str(),
                (stepInFlight() ? backendName_ : sim.backendName()).c_str());
    ImGui::Separator();
    ImGui::Text("frame %d  (%s)", metrics_.frame, playing_ ? "playing" : "paused");
    ImGui::Text("ms: total %.1f  elements %.1f  solve %.1f", metrics_.msTotal, metrics_.msElements,
                metrics_.msSolve);
    ImGui::Text("    fracture %.1f  plastic %.1f  surface %.1f", metrics_.msFracture,
                metrics_.msPlastic, msSurface_);
    ImGui::Text("residual %.2e   volume change %+.3f %%", metrics_.residual,
                metrics_.volumeChangePct);
    ImGui::Text("pieces %d   damaged edges %d   anchored %zu", metrics_.pieces,
                metrics_.damagedEdges, anchored_.size());
    if (metrics_.warnings > 0)
      ImGui::TextColored(ImVec4(1, 0.6f, 0.2f, 1), "step retries: %d", metrics_.warnings);
    ImGui::Text("history %.1f MB, %zu recorded events", session_->historyBytes() / 1048576.0,
                session_->recording().size());
    for (const std::string& note : stepInFlight() ? notes_ : sim.notes())
      ImGui::TextDisabled("%s", note.c_str());
  }
  if (!status_.empty()) ImGui::TextDisabled("%s", status_.c_str());
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void SculptApp::frameHoveredPiece() {
  // Shift+F: frame the piece under the cursor (after cuts, one fragment fills the view).
  const Simulation& sim = session_->simulation();
  const std::optional<RayHit> hit =
      controller_->pick(controller_->cursorX(), controller_->cursorY());
  if (!hit) return;
  const int piece = sim.pieceOf(sim.surface().cellVertex[hit->face]);
  std::vector<Vec3> points;
  for (int v = 0; v < sim.model().numVertices(); ++v)
    if (sim.pieceOf(v) == piece) points.push_back(sim.state().x[v]);
  camera_.frame(boundingBox(points));
}

void SculptApp::applySceneSettings() {
  finishStep();
  try {
    SceneSettings s = editing_;
    s.solver.grid = grid_;
    const SceneDescription scene = editScene(session_->scene(), s);
    const TetMesh mesh = session_->simulation().model().mesh;
    OpenedSession opened;
    opened.session = std::make_unique<SculptSession>(scene, mesh);
    opened.session->markSceneEdited();
    opened.camera = camera_.pose();
    adopt(std::move(opened), currentFile_);
    report("restarted with the new settings");
  } catch (const std::exception& e) {
    fail(std::string("scene settings: ") + e.what());  // the running session stays
  }
}

void SculptApp::drawScenePanel() {
  if (!session_) return;
  ImGui::SetNextWindowPos(ImVec2(10, 470), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
  ImGui::Begin("Scene settings", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  MaterialDesc& m = editing_.material;
  static const char* presets[] = {"clay", "rubber", "flesh", "steel"};
  int preset = 0;
  for (int i = 0; i < 4; ++i)
    if (m.preset == presets[i]) preset = i;
  if (ImGui::Combo("preset", &preset, presets, 4)) m = materialPreset(presets[preset]);
  pickEnum("model", m.model,
           {MaterialModel::Corotational, MaterialModel::StVK, MaterialModel::StableNeoHookean},
           materialModelName);
  ImGui::InputDouble("Young's modulus (Pa)", &m.youngsModulus, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("Poisson ratio", &m.poissonRatio, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("density (kg/m^3)", &m.density, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("yield stress (Pa, 0: elastic)", &m.yieldStress, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("hardening (Pa)", &m.hardening, 0.0, 0.0, "%.4g");
  ImGui::Checkbox("fracture", &editing_.fracture);
  if (editing_.fracture)
    ImGui::InputDouble("threshold (Pa, 0: material's)", &editing_.fractureThreshold, 0.0, 0.0,
                       "%.4g");
  ImGui::Separator();
  SolverDesc& v = editing_.solver;
  pickEnum("solver", v.type, {SolverType::Multigrid, SolverType::Reference}, solverTypeName);
  ImGui::InputText("grid (e.g. 50/1000/all)", grid_, sizeof grid_);
  ImGui::InputInt("fine sweeps", &v.fineSweeps);
  ImGui::InputInt("coarse iterations", &v.coarseIterations);
  pickEnum("smoother", v.smoother, {Smoother::GaussSeidel, Smoother::Jacobi}, smootherName);
  pickEnum("coarse solver", v.coarseSolver, {CoarseSolver::Cg, CoarseSolver::Cholesky},
           coarseSolverName);
  pickEnum("backend", v.backend, {BackendRequest::Auto, BackendRequest::Cpu, BackendRequest::Cuda},
           backendRequestName);
  if (ImGui::Button("Apply (restarts the simulation)")) applySceneSettings();
  ImGui::SameLine();
  if (ImGui::Button("Revert")) {
    editing_ = sceneSettings(session_->scene());
    std::snprintf(grid_, sizeof grid_, "%s", editing_.solver.grid.c_str());
  }
  ImGui::End();
}

void SculptApp::drawCursor() {
  if (!controller_ || (ImGui::GetIO().WantCaptureMouse && !scripted_)) return;
  int width = 1, height = 1;
  glfwGetWindowSize(window_, &width, &height);
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const double x = controller_->cursorX(), y = controller_->cursorY();
  if (toolSettings_.tool == Tool::Knife) {
    draw->AddLine(ImVec2(float(x) - 8, float(y) + 8), ImVec2(float(x) + 8, float(y) - 8),
                  IM_COL32(255, 80, 60, 255), 2.0f);
    return;
  }
  if (stepInFlight()) return;  // no pick while the surface is being recomputed
  const std::optional<RayHit> hit = controller_->hover();
  if (!hit) return;
  // The brush radius on screen: project a point one radius away on the plane facing the camera.
  const Vec3 side = camera_.forward().cross(Vec3::UnitY()).normalized();
  const Vec3 c = camera_.project(hit->point, width, height);
  const Vec3 r = camera_.project(hit->point + toolSettings_.radius * side, width, height);
  const float pixels = static_cast<float>((r - c).head<2>().norm());
  const ImU32 color =
      toolSettings_.tool == Tool::AnchorPaint || toolSettings_.tool == Tool::AnchorErase
          ? IM_COL32(60, 110, 255, 255)
          : IM_COL32(255, 255, 255, 220);
  draw->AddCircle(ImVec2(float(c.x()), float(c.y())), pixels, color, 48, 1.5f);
  if (toolSettings_.symmetry) {
    const Symmetry plane{toolSettings_.symmetryAxis, toolSettings_.symmetryOffset};
    const Vec3 m = camera_.project(plane.point(hit->point), width, height);
    draw->AddCircle(ImVec2(float(m.x()), float(m.y())), pixels, IM_COL32(255, 255, 255, 110), 48,
                    1.0f);
  }
}

void SculptApp::drawDialogs() {
  if (busy()) {
    ImGui::OpenPopup("Loading");
  }
  if (ImGui::BeginPopupModal("Loading", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    std::lock_guard<std::mutex> lock(progressMutex_);
    const char spinner[] = "|/-\\";
    ImGui::Text("%c %s", spinner[static_cast<int>(ImGui::GetTime() * 8) % 4], progress_.c_str());
    if (!busy()) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (showError_) {
    ImGui::OpenPopup("Error");
    showError_ = false;
  }
  if (ImGui::BeginPopupModal("Error", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted(error_.c_str());
    if (ImGui::Button("OK") || scripted_) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (askRecovery_ && !busy()) {
    ImGui::OpenPopup("Recover");
    askRecovery_ = false;
  }
  if (ImGui::BeginPopupModal("Recover", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("Galsculpt did not close normally. Recover the autosaved work?");
    ImGui::TextDisabled("%s", recoverable_.front().string().c_str());
    if (ImGui::Button("Recover")) {
      startLoading(recoverable_.front());
      // Keep the file until the recovered work is saved elsewhere or autosaved anew.
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      for (const fs::path& f : recoverable_) recovery_->remove(f);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Later")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  static const char* titles[] = {
      "", "Open", "Save project", "Save recording", "Export surface", "Export tet mesh"};
  static const char* hints[] = {"",
                                "a project (.gsproj), scene (.json) or mesh",
                                "a .gsproj file",
                                "a .json playback script",
                                ".obj, .ply, .stl, .gltf or .glb",
                                "a path without extension (writes .node/.ele/.face/.damage/.vtk)"};
  if (dialog_ != PathDialog::None) {
    ImGui::OpenPopup("Path");
    if (path_[0] == '\0') {
      const std::string stem = session_ ? session_->scene().name : "galsculpt";
      const char* defaults[] = {"", "", ".gsproj", "-recording.json", ".obj", "-tets"};
      const std::string guess = dialog_ == PathDialog::Open
                                    ? currentFile_.string()
                                    : stem + defaults[static_cast<int>(dialog_)];
      std::snprintf(path_, sizeof path_, "%s", guess.c_str());
    }
  }
  if (ImGui::BeginPopupModal("Path", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    const int d = static_cast<int>(dialog_);
    ImGui::Text("%s: %s", titles[d], hints[d]);
    ImGui::SetNextItemWidth(520);
    const bool enter =
        ImGui::InputText("##path", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::Button("OK") || enter) {
      static const char* commands[] = {"",       "open",       "save_project", "save_recording",
                                       "export", "export_tets"};
      const std::string path = path_;
      const std::string command = commands[d];
      dialog_ = PathDialog::None;
      path_[0] = '\0';
      ImGui::CloseCurrentPopup();
      runCommand(command, path);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      dialog_ = PathDialog::None;
      path_[0] = '\0';
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

void SculptApp::drawUi() {
  drawMenu();
  drawToolsPanel();
  drawScenePanel();
  drawOverlay();
  drawCursor();
  drawDialogs();
}

void SculptApp::autosave() {
  if (!session_ || stepInFlight() || options_.autosaveSeconds <= 0.0 || !session_->dirty()) return;
  if (Clock::now() - lastAutosave_ < std::chrono::duration<double>(options_.autosaveSeconds))
    return;
  lastAutosave_ = Clock::now();
  try {
    recovery_->save(*session_, camera_.pose());
  } catch (const std::exception& e) {
    status_ = std::string("autosave failed: ") + e.what();
  }
}

void SculptApp::finish() {
  finishStep();
  if (session_) {
    if (options_.saveProjectOnExit)
      runCommand("save_project", options_.saveProjectOnExit->string());
    if (options_.saveRecordingOnExit)
      runCommand("save_recording", options_.saveRecordingOnExit->string());
  }
  recovery_->remove(recovery_->ownFile());  // a normal exit leaves nothing to recover
}

void SculptApp::run() {
  while (!glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    collectStep();
    finishLoading();
    runScriptStep();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    int width = 1, height = 1;
    glfwGetWindowSize(window_, &width, &height);
    if (controller_) controller_->setViewport(width, height);
    processInput();
    advanceSimulation();
    updateScene();
    drawUi();
    ImGui::Render();
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    renderer_.draw(camera_, fbWidth, fbHeight, RenderOptions{wireframe_, 7.0f});
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    takeScreenshot(fbWidth, fbHeight);
    glfwSwapBuffers(window_);
    autosave();
  }
  if (busy()) loading_.wait();
  finishLoading();
  finish();
}

SculptApp* appOf(GLFWwindow* w) {
  return static_cast<SculptApp*>(glfwGetWindowUserPointer(w));
}

void onCursor(GLFWwindow* w, double x, double y) {
  InputEvent e;
  e.kind = InputEvent::Kind::Move;
  e.x = x;
  e.y = y;
  appOf(w)->queue().push_back(e);
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
  appOf(w)->queue().push_back(e);
}

void onScroll(GLFWwindow* w, double, double dy) {
  InputEvent e;
  e.kind = InputEvent::Kind::Scroll;
  e.y = dy;
  appOf(w)->queue().push_back(e);
}

void onKey(GLFWwindow* w, int key, int, int action, int mods) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  // GLFW's codes are ASCII for letters, digits, space, '.', '[' and ']'.
  e.key = key == GLFW_KEY_ESCAPE ? kKeyEscape : key;
  e.shift = mods & GLFW_MOD_SHIFT;
  e.ctrl = mods & GLFW_MOD_CONTROL;
  appOf(w)->queue().push_back(e);
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
  glfwWindowHint(GLFW_SAMPLES, 4);
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
    glfwSetWindowUserPointer(window, &app);
    // Ours first: ImGui's backend chains to callbacks installed before it.
    glfwSetCursorPosCallback(window, onCursor);
    glfwSetMouseButtonCallback(window, onButton);
    glfwSetScrollCallback(window, onScroll);
    glfwSetKeyCallback(window, onKey);
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
