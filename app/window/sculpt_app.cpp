#include "app/window/sculpt_app.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstring>

#include "app/render/gl.h"
#include "app/render/offscreen_context.h"
#include "app/render/render_mesh.h"
#include "engine/session/project_file.h"
#include "engine/surface/surface_io.h"
#include "solver/frame/timing.h"

namespace galsculpt {

namespace fs = std::filesystem;

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
  opener_.start(file, options_.backend);
}

void SculptApp::finishLoading() {
  if (!opener_.ready()) return;
  finishStep();  // the old session's frame ends before the new session replaces it
  try {
    adopt(opener_.take(), opener_.file());
  } catch (const std::exception& e) {
    // The current session (if any) stays; the user can open another file.
    fail(std::string("cannot open ") + opener_.file().string() + ":\n" + e.what());
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
      if (!(io.WantCaptureKeyboard && !scripted_) && !busy()) {
        if (const auto c = keyCommand(e.key, e.ctrl, e.shift, projectFile_.string())) execute(*c);
      }
      break;
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
      // A script names its paths: without one it fails as a command would, no dialog.
      if (takesPath(s.command) && s.argument.empty())
        fail(std::string(scriptCommandName(s.command)) + ": needs a path (\"argument\")");
      else
        execute(Command{s.command, s.argument});
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
  if (frames_.inFlight()) metrics_ = frames_.wait();
  // Read between frames: a frame in flight may change the backend (a device failure) and notes.
  if (session_) {
    backendName_ = session_->simulation().backendName();
    notes_ = session_->simulation().notes();
  }
}

void SculptApp::collectStep() {
  if (frames_.ready()) finishStep();
}

void SculptApp::advanceSimulation() {
  // Launch only: a finished frame is collected at the top of the loop, before input, so input
  // that waited for it goes through before the next frame starts.
  if (stepInFlight() || !session_ || busy()) return;
  session_->setCamera(camera_.pose());
  if (playing_ || stepOnce_) {
    stepOnce_ = false;
    // The frame runs on a worker thread: the window keeps drawing and navigating meanwhile.
    frames_.start(*session_);
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
  msSurface_ = msSince(start);
  std::vector<double> values;
  if (style_.view == SurfaceView::Damage) {
    values = sim.vertexDamage();
    style_.scaleMax = 1.0;
  } else if (style_.view == SurfaceView::Stress) {
    values = sim.vertexStress();
    // The hottest colour at the 98th percentile: a few peaks do not wash the rest out.
    std::vector<double> sorted = values;
    const size_t k = sorted.size() * 98 / 100;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
    style_.scaleMax = std::max(sorted[k], 1e-9);
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
      execute(Command{AppCommand::SaveProject, options_.saveProjectOnExit->string()});
    if (options_.saveRecordingOnExit)
      execute(Command{AppCommand::SaveRecording, options_.saveRecordingOnExit->string()});
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
  opener_.wait();
  finishLoading();
  finish();
}

}  // namespace galsculpt
