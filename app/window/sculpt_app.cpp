#include "app/window/sculpt_app.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstring>

#include "app/render/gl.h"
#include "app/render/offscreen_context.h"
#include "app/render/render_mesh.h"
#include "app/window/sub_buffer_present.h"
#include "engine/session/project_file.h"
#include "engine/surface/surface_io.h"
#include "solver/frame/parallel.h"
#include "solver/frame/timing.h"
#include "solver/io/stop_request.h"

#include <time.h>

namespace galsculpt {

namespace fs = std::filesystem;

namespace {
// This thread's CPU time (ms): what a drawn frame costs the window's thread, waits excluded.
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}
}  // namespace

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

// What the window shows (its front buffer, read back from the X server by Mesa's software
// rasterizer) against the whole back buffer, the picture it should show: a partial present that
// left a stale part would differ (GALSCULPT_CHECK_PRESENT=1; the UI tests use it).
void SculptApp::checkPresent(int width, int height) {
  const size_t size = static_cast<size_t>(width) * height * 4;
  std::vector<std::uint8_t> back(size);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, back.data());
  const std::vector<std::uint8_t> screen = present_->readScreen(width, height);
  long differing = screen.size() == size ? 0 : width * static_cast<long>(height);
  for (size_t i = 0; screen.size() == size && i < size; i += 4) {
    if (back[i] != screen[i] || back[i + 1] != screen[i + 1] || back[i + 2] != screen[i + 2])
      ++differing;
  }
  ++presentChecks_;
  presentDiffering_ += differing;
}

bool SculptApp::init(std::string* error) {
  if (!renderer_.init(error)) return false;
  renderer_.setCached(softwareRenderer_);
  if (softwareRenderer_ && partialRedraws_) {
    present_ = std::make_unique<SubBufferPresent>(window_);
    if (!present_->supported()) present_.reset();
  }
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
  opener_.start(file, options_.solver);
}

void SculptApp::finishLoading() {
  // The old session's frame ends before the new session replaces it: until then, keep drawing.
  if (!opener_.ready() || stepInFlight()) return;
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
  shown_ = FrameView{};  // the new body is drawn at once (updateScene)
  frameInput_.reset();
  editing_ = sceneSettings(session_->scene());
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
      if (std::string notice = controller_->takeNotice(); !notice.empty()) report(notice);
      break;
    case InputEvent::Kind::Scroll:
      if (controller_ && !(io.WantCaptureMouse && !scripted_)) controller_->scroll(e.y);
      break;
    case InputEvent::Kind::Key:
      if (!(io.WantCaptureKeyboard && !scripted_) && !busy()) {
        if (const auto c = keyCommand(e.key, e.ctrl, e.shift, projectFile_.string())) execute(*c);
      }
      break;
    case InputEvent::Kind::Command:
      execute(e.command);
      break;
  }
}

void SculptApp::enqueue(InputEvent e) {
  e.at = Clock::now();
  ++wakeups_;
  if (e.kind == InputEvent::Kind::Move) {
    cursorX_ = e.x;
    cursorY_ = e.y;
    if (trailing_) trail_.emplace_back(static_cast<float>(e.x), static_cast<float>(e.y));
  } else if (e.kind == InputEvent::Kind::Button && e.button == MouseButton::Left) {
    const bool overPanel = ImGui::GetIO().WantCaptureMouse && !scripted_;
    trailing_ = e.pressed && toolSettings_.tool == Tool::Knife && !overPanel && session_;
    trail_.clear();
    if (trailing_) trail_.emplace_back(static_cast<float>(cursorX_), static_cast<float>(cursorY_));
  }
  queue_.push_back(e);
}

void SculptApp::runScriptStep() {
  if (!scripted_ || busy()) return;
  if (scriptWait_ > 0) {
    --scriptWait_;
    return;
  }
  if (scriptWaitViews_ >= 0) {
    if (viewsShown_ < scriptWaitViews_) return;
    scriptWaitViews_ = -1;
  }
  if (scriptNext_ >= script_.size()) {
    if (queue_.empty() && pendingScreenshot_.empty()) glfwSetWindowShouldClose(window_, 1);
    return;
  }
  // A screenshot shows what the steps before it did: it waits until their input has acted
  // and the view that holds it is on the screen (input waits for the frame in flight).
  if (script_[scriptNext_].kind == InputStep::Kind::Command &&
      script_[scriptNext_].command == AppCommand::Screenshot && inputNotYetShown())
    return;
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
    case InputStep::Kind::WaitFrames:
      if (realtime_)
        scriptWaitViews_ = viewsShown_ + s.frames;
      else
        scriptWait_ = s.frames;
      break;
    case InputStep::Kind::Move:
      e.kind = InputEvent::Kind::Move;
      for (const auto& [fx, fy] : s.points) {
        e.x = fx * width;
        e.y = fy * height;
        enqueue(e);
      }
      break;
    case InputStep::Kind::Press:
    case InputStep::Kind::Release:
      e.kind = InputEvent::Kind::Button;
      e.button = s.button;
      e.pressed = s.kind == InputStep::Kind::Press;
      enqueue(e);
      break;
    case InputStep::Kind::Scroll:
      e.kind = InputEvent::Kind::Scroll;
      e.y = s.scroll;
      enqueue(e);
      break;
    case InputStep::Kind::Key:
      e.kind = InputEvent::Kind::Key;
      e.key = s.key;
      enqueue(e);
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

bool SculptApp::restyled() const {
  return shown_.style.view != style_.view || shown_.style.tintCracks != style_.tintCracks;
}

bool SculptApp::inputNotYetShown() const {
  return !queue_.empty() || pendingInput_ || frameInput_ || (session_ && restyled());
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
    case InputEvent::Kind::Command:
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
    const InputEvent& e = events[i];
    if (stepInFlight() && (!controller_ || !navigationOnly(e))) break;
    // What acts on the session shows in the next view: the latency runs from its arrival.
    if (controller_ && !navigationOnly(e) && !pendingInput_) pendingInput_ = e.at;
    handleEvent(e);
  }
  queue_.assign(events.begin() + static_cast<long>(i), events.end());
}

void SculptApp::finishStep() {
  if (!frames_.inFlight()) return;
  FrameView view = frames_.wait();
  simulationRate_.tick(Clock::now());
  ++viewsShown_;
  ++runFrames_;
  runFrameMs_.add(view.metrics.msTotal);
  runViewMs_.add(view.msView);
  if (playing_) lastReadyAt_ = view.readyAt;
  show(std::move(view));
}

void SculptApp::collectStep() {
  if (frames_.ready()) finishStep();
}

// A finished frame's view goes on the screen (uploaded now, drawn this window frame).
void SculptApp::show(FrameView view) {
  renderer_.setMesh(view.mesh);
  renderer_.setPoints(view.anchors, kAnchorColor);
  shown_ = std::move(view);
  shown_.mesh = RenderMesh{};  // uploaded: the window keeps only what it reads

  if (frameInput_ && (!drawnInput_ || *frameInput_ < *drawnInput_)) drawnInput_ = frameInput_;
  frameInput_.reset();
}

void SculptApp::advanceSimulation() {
  // Launch only: a finished frame is collected at the top of the loop, before input, so input
  // that waited for it goes through before the next frame starts.
  if (!frameShouldStart()) return;
  session_->setCamera(camera_.pose());
  stepOnce_ = false;
  frameInput_ = pendingInput_;
  pendingInput_.reset();
  if (playing_ && lastReadyAt_)
    runIdleMs_.add(std::chrono::duration<double, std::milli>(Clock::now() - *lastReadyAt_).count());
  lastReadyAt_.reset();
  // The frame and its view run on a worker thread: the window keeps drawing and navigating
  // meanwhile, and wakes when they are done.
  frames_.start(*session_, style_, [] { glfwPostEmptyEvent(); });
  if (scripted_ && !realtime_) finishStep();  // scripted input counts frames exactly
}

bool SculptApp::frameShouldStart() const {
  return session_ && !stepInFlight() && !busy() && (playing_ || stepOnce_);
}

// Between frames, when what is on the screen is not the session's state: at once after opening
// a file, and while paused (tools, undo, a view change). While playing, the next frame's view
// brings the tools' effect, built on the worker.
void SculptApp::updateScene() {
  if (!session_ || stepInFlight() || busy()) return;
  if (shown_.valid && !restyled() && frameShouldStart()) return;
  if (!viewIsCurrent(shown_, *session_, style_))
    show(makeFrameView(*session_, style_, shown_.metrics));
  // What acted between frames is on the screen from this draw, whether it changed the body
  // (a tool, undo) or only the panels (a tool chosen).
  if (pendingInput_ && (!drawnInput_ || *pendingInput_ < *drawnInput_)) drawnInput_ = pendingInput_;
  pendingInput_.reset();
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
  if (stopRequested() && session_ && session_->dirty() && options_.autosaveSeconds > 0.0) {
    // Ended by Ctrl-C or SIGTERM (a logout, a shutdown): the work is kept for the next start's
    // recovery offer, as after a crash, instead of being lost.
    try {
      recovery_->save(*session_, camera_.pose());
      log_ << "stopped by " << signalName(stopSignal())
           << "; the session is kept for recovery: " << recovery_->ownFile().string() << '\n';
    } catch (const std::exception& e) {
      log_ << "stopped by " << signalName(stopSignal())
           << "; the session could not be kept: " << e.what() << '\n';
    }
  } else {
    recovery_->remove(recovery_->ownFile());  // a normal exit leaves nothing to recover
  }
  // What the run cost, measured (docs/benchmarks.md, "Threads and the window"): the window's draws,
  // the simulation's frames in the window, and input to screen.
  const double seconds = std::chrono::duration<double>(Clock::now() - runStart_).count();
  char line[768];
  std::snprintf(line, sizeof line,
                "window: %d draws, %.1f a second, median %.1f ms between draws, %.2f ms of its "
                "thread a draw; simulation: %d frames, median %.1f ms a frame; input to screen: "
                "median %.0f ms over %zu samples; %d threads; between frames: median %.1f ms "
                "building the view, %.1f ms waiting for the window; during strokes: %.1f draws "
                "a second over %.1f s",
                runDraws_, runDraws_ / std::max(seconds, 1e-9), runWindowMs_.median(),
                runWindowCpuMs_.median(), runFrames_, runFrameMs_.median(), runLatencyMs_.median(),
                runLatencyMs_.size(), threadCount(), runViewMs_.median(), runIdleMs_.median(),
                strokeIntervals_ / std::max(strokeSeconds_, 1e-9), strokeSeconds_);
  log_ << line << '\n';
  if (checkPresent_)
    log_ << "present check: " << presentChecks_ << " partial draws, " << presentDiffering_
         << " pixels on the screen unlike the picture\n";
}

void SculptApp::run() {
  // Ctrl-C or SIGTERM closes the window as its close button does (stop_request.h).
  while (!glfwWindowShouldClose(window_) && !stopRequested()) {
    waitForWork();
    // Draws keep to a grid of the period: a late one brings the next forward, so the rate holds
    // (one more than a period late, the grid starts again from now).
    const Clock::time_point now = Clock::now();
    nextDraw_ = (now - nextDraw_ > drawPeriod() ? now : nextDraw_) + drawPeriod();
    const double cpuAtStart = threadCpuMs();
    runScriptStep();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    betweenFrames();
    drawUi();
    ImGui::Render();
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    const std::optional<std::vector<PixelRect>> changed = drawScreen(fbWidth, fbHeight);
    takeScreenshot(fbWidth, fbHeight);
    if (changed) {
      present_->present(*changed);
      if (checkPresent_) checkPresent(fbWidth, fbHeight);
    } else {
      glfwSwapBuffers(window_);
    }
    afterSwap(cpuAtStart);
    autosave();
  }
  opener_.wait();
  while (frames_.inFlight()) finishStep();
  finishLoading();
  finish();
}

// The scene and the panels into the back buffer. With the scene cached (a software rasterizer)
// and the window shown by copying parts of a back buffer that is never swapped, only what
// changed is drawn again (partial_redraw.h), and the parts to copy are returned; otherwise
// everything is drawn, for a swap.
std::optional<std::vector<PixelRect>> SculptApp::drawScreen(int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const RenderOptions options{wireframe_, 7.0f};
  ImDrawData* ui = ImGui::GetDrawData();
  PixelRect sceneChanged;
  if (!renderer_.cached()) {
    renderer_.draw(camera_, width, height, options);
    ImGui_ImplOpenGL3_RenderDrawData(ui);
    return std::nullopt;
  }
  if (!renderer_.update(camera_, width, height, options, &sceneChanged)) {
    ImGui_ImplOpenGL3_RenderDrawData(ui);  // drawn straight to the screen: no cache here
    return std::nullopt;
  }
  // Everything is drawn and shown after a resize or an expose, and without partial presents.
  const bool full = !present_ || presentAll_ || width != drawnWidth_ || height != drawnHeight_;
  presentAll_ = false;
  drawnWidth_ = width;
  drawnHeight_ = height;
  RedrawPlan plan = panelRedraws_.plan(*ui, sceneChanged, width, height, full);
  renderer_.present(plan.restore);
  DrawDataSubset subset(*ui, plan.lists);
  ImGui_ImplOpenGL3_RenderDrawData(subset.get());
  if (!present_) return std::nullopt;
  return std::move(plan.restore);
}

// A finished frame is taken, the input that waited for it acts, the screen's view catches up
// and the next frame starts: in the window's loop, and also while the window waits for its
// next draw, so that the simulation never waits for the window's rate.
void SculptApp::betweenFrames() {
  collectStep();
  finishLoading();
  int width = 1, height = 1;
  glfwGetWindowSize(window_, &width, &height);
  if (controller_) controller_->setViewport(width, height);
  processInput();
  if (applySettings_ && !stepInFlight()) {
    applySettings_ = false;
    applySceneSettings();
  }
  updateScene();
  // Here, between two frames, is where a playing simulation can be saved at all: elsewhere a
  // frame is in flight almost always.
  autosave();
  advanceSimulation();
}

void SculptApp::afterSwap(double cpuAtStart) {
  const Clock::time_point now = Clock::now();
  const double cpu = threadCpuMs() - cpuAtStart;
  windowCpuMs_.add(cpu);
  runWindowCpuMs_.add(cpu);
  const bool inStroke = controller_ && controller_->strokeActive();
  if (lastDraw_ != Clock::time_point{}) {
    const double ms = std::chrono::duration<double, std::milli>(now - lastDraw_).count();
    windowMs_.add(ms);
    runWindowMs_.add(ms);
    if (inStroke && lastDrawInStroke_) {
      ++strokeIntervals_;
      strokeSeconds_ += ms / 1000.0;
    }
  }
  lastDrawInStroke_ = inStroke;
  lastDraw_ = now;
  windowRate_.tick(now);
  ++runDraws_;
  if (drawnInput_) {
    const double ms = std::chrono::duration<double, std::milli>(now - *drawnInput_).count();
    latencyMs_.add(ms);
    runLatencyMs_.add(ms);
  }
  drawnInput_.reset();
}

// The window draws at 60 Hz (30 on a software rasterizer) while something moves on it (input in the
// last moments, a stroke, loading, a script) and otherwise only when a frame's view arrives or an
// event comes: paused and untouched, it sleeps in glfwWaitEvents.
bool SculptApp::wantsSteadyDraws() const {
  if (scripted_ || busy() || redraw_ > 0 || stepOnce_) return true;
  if (controller_ && !controller_->navigating()) return true;
  return Clock::now() - lastInput_ < std::chrono::milliseconds(500);
}

Clock::duration SculptApp::drawPeriod() const {
  const double windowHz = softwareRenderer_ ? 30.0 : 60.0;
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / windowHz));
}

void SculptApp::waitForWork() {
  if (scripted_ && !realtime_) {  // synchronous scripts run as fast as they can
    glfwPollEvents();
    return;
  }
  const Clock::time_point next = nextDraw_;
  if (redraw_ > 0) --redraw_;
  for (;;) {
    if (glfwWindowShouldClose(window_) || stopRequested()) break;
    const bool steady = wantsSteadyDraws();
    if (frames_.ready() && steady) {
      betweenFrames();  // drawn at the next tick
      continue;
    }
    if (frames_.ready() || frameShouldStart()) break;
    if (!queue_.empty() && !stepInFlight()) break;  // input that waited for a frame
    const double left = steady ? std::chrono::duration<double>(next - Clock::now()).count() : 1.0;
    if (left <= 0.0) break;
    const std::size_t before = wakeups_;
    glfwWaitEventsTimeout(left);
    if (wakeups_ != before) {
      lastInput_ = Clock::now();
      redraw_ = 2;  // ImGui settles its hover and its layout over a frame or two
    } else if (!steady) {
      autosave();  // idle: its clock still runs
    }
  }
  glfwPollEvents();
}

}  // namespace galsculpt
