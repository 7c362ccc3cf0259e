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

bool SculptApp::init(std::string* error) {
  if (!renderer_.init(error)) return false;
  renderer_.setCached(pacer_.software());
  presenter_.init(window_, pacer_.software());
  playing_ = options_.startPlaying;
  recovery_ = std::make_unique<RecoveryStore>();
  if (options_.offerRecovery) panels_.offerRecovery(recovery_->orphans());
  if (options_.inputScript) script_.load(loadInputScript(*options_.inputScript));
  opener_.start(options_.file, options_.solver);
  return true;
}

void SculptApp::report(const std::string& message) {
  panels_.setStatus(message);
  log_ << message << '\n';
}

void SculptApp::fail(const std::string& message) {
  panels_.showError(message);
  log_ << "error: " << message << '\n';
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
  meters_.frameDropped();
  panels_.editing() = sceneSettings(session_->scene());
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
      if (!controller_ || (e.pressed && io.WantCaptureMouse && !script_.active()) || busy()) break;
      controller_->mouseButton(e.button, e.pressed, e.shift);
      if (std::string notice = controller_->takeNotice(); !notice.empty()) report(notice);
      break;
    case InputEvent::Kind::Scroll:
      if (controller_ && !(io.WantCaptureMouse && !script_.active())) controller_->scroll(e.y);
      break;
    case InputEvent::Kind::Key:
      if (!(io.WantCaptureKeyboard && !script_.active()) && !busy()) {
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
  pacer_.wake();
  if (e.kind == InputEvent::Kind::Move) {
    panels_.cursorAt(e.x, e.y);
  } else if (e.kind == InputEvent::Kind::Button && e.button == MouseButton::Left) {
    const bool overPanel = ImGui::GetIO().WantCaptureMouse && !script_.active();
    panels_.knifeStroke(e.pressed && toolSettings_.tool == Tool::Knife && !overPanel && session_);
  }
  queue_.push_back(e);
}

void SculptApp::runScriptStep() {
  if (!script_.active() || busy()) return;
  const InputScriptRunner::Turn turn = script_.next(meters_.framesArrived(), inputNotYetShown());
  if (turn.kind == InputScriptRunner::Turn::Kind::Done) {
    if (queue_.empty() && !presenter_.screenshotPending()) glfwSetWindowShouldClose(window_, 1);
    return;
  }
  if (turn.kind == InputScriptRunner::Turn::Kind::Hold) return;
  const InputStep& s = *turn.step;
  int width = 1, height = 1;
  glfwGetWindowSize(window_, &width, &height);
  InputEvent e;
  e.shift = s.shift;
  e.ctrl = s.ctrl;
  switch (s.kind) {
    case InputStep::Kind::Wait:
    case InputStep::Kind::WaitFrames:
      break;  // the runner's own
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
  return !queue_.empty() || meters_.inputWaiting() || (session_ && restyled());
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
    if (controller_ && !navigationOnly(e)) meters_.inputActs(e.at);
    handleEvent(e);
  }
  queue_.assign(events.begin() + static_cast<long>(i), events.end());
}

void SculptApp::finishStep() {
  if (!frames_.inFlight()) return;
  FrameView view = frames_.wait();
  meters_.frameArrives(view.metrics.msTotal, view.msView, view.readyAt, playing_);
  show(std::move(view));
}

// A finished frame's view goes on the screen (uploaded now, drawn this window frame).
void SculptApp::show(FrameView view) {
  renderer_.setMesh(view.mesh);
  renderer_.setPoints(view.anchors, kAnchorColor);
  shown_ = std::move(view);
  shown_.mesh = RenderMesh{};  // uploaded: the window keeps only what it reads

  meters_.frameShown();
}

void SculptApp::advanceSimulation() {
  // Launch only: a finished frame is collected at the top of the loop, before input, so input
  // that waited for it goes through before the next frame starts.
  if (!frameShouldStart()) return;
  session_->setCamera(camera_.pose());
  stepOnce_ = false;
  meters_.frameStarts(playing_);
  // The frame and its view run on a worker thread: the window keeps drawing and navigating
  // meanwhile, and wakes when they are done.
  frames_.start(*session_, style_, [] { glfwPostEmptyEvent(); });
  if (script_.active() && !script_.realtime())
    finishStep();  // scripted input counts frames exactly
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
  meters_.actedBetweenFramesShown();
}

void SculptApp::autosave() {
  if (!session_ || stepInFlight() || options_.autosaveSeconds <= 0.0 || !session_->dirty()) return;
  if (Clock::now() - lastAutosave_ < std::chrono::duration<double>(options_.autosaveSeconds))
    return;
  lastAutosave_ = Clock::now();
  try {
    recovery_->save(*session_, camera_.pose());
  } catch (const std::exception& e) {
    panels_.setStatus(std::string("autosave failed: ") + e.what());
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
  log_ << meters_.runSummary(threadCount()) << '\n';
  if (const std::string check = presenter_.checkSummary(); !check.empty()) log_ << check << '\n';
}

void SculptApp::run() {
  // Ctrl-C or SIGTERM closes the window as its close button does (stop_request.h).
  while (!glfwWindowShouldClose(window_) && !stopRequested()) {
    waitForWork();
    // Draws keep to a grid of the period: a late one brings the next forward, so the rate holds
    // (one more than a period late, the grid starts again from now).
    pacer_.drawStarts(Clock::now());
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
    const std::optional<std::vector<PixelRect>> changed =
        presenter_.draw(renderer_, camera_, RenderOptions{wireframe_, 7.0f}, fbWidth, fbHeight);
    try {
      if (const std::optional<std::string> written = presenter_.writeScreenshot(fbWidth, fbHeight))
        report("wrote " + *written);
    } catch (const std::exception& e) {
      fail(e.what());
    }
    presenter_.present(window_, changed, fbWidth, fbHeight);
    meters_.drawn(threadCpuMs() - cpuAtStart, controller_ && controller_->strokeActive());
    autosave();
  }
  opener_.wait();
  while (frames_.inFlight()) finishStep();
  finishLoading();
  finish();
}

// The panels read the window's state through a context and act through execute.
void SculptApp::drawUi() {
  PanelContext c{window_,
                 session_.get(),
                 controller_.get(),
                 toolSettings_,
                 style_,
                 wireframe_,
                 playing_,
                 script_.active(),
                 shown_,
                 camera_,
                 meters_,
                 opener_,
                 *recovery_,
                 currentFile_,
                 projectFile_,
                 [this](const Command& command) { execute(command); }};
  panels_.draw(c);
}

// A finished frame is taken, the input that waited for it acts, the screen's view catches up
// and the next frame starts: in the window's loop, and also while the window waits for its
// next draw, so that the simulation never waits for the window's rate.
void SculptApp::betweenFrames() {
  if (frames_.ready()) finishStep();
  finishLoading();
  int width = 1, height = 1;
  glfwGetWindowSize(window_, &width, &height);
  if (controller_) controller_->setViewport(width, height);
  processInput();
  if (!stepInFlight() && panels_.takeApply()) applySceneSettings();
  updateScene();
  // Here, between two frames, is where a playing simulation can be saved at all: elsewhere a
  // frame is in flight almost always.
  autosave();
  advanceSimulation();
}

// The window draws at 60 Hz (30 on a software rasterizer) while something moves on it (input in the
// last moments, a stroke, loading, a script) and otherwise only when a frame's view arrives or an
// event comes: paused and untouched, it sleeps in glfwWaitEvents.
bool SculptApp::wantsSteadyDraws() const {
  if (script_.active() || busy() || pacer_.settling() || stepOnce_) return true;
  if (controller_ && !controller_->navigating()) return true;
  return pacer_.recentInput(Clock::now());
}

void SculptApp::waitForWork() {
  if (script_.active() && !script_.realtime()) {  // synchronous scripts run as fast as they can
    glfwPollEvents();
    return;
  }
  const Clock::time_point next = pacer_.nextDraw();
  pacer_.drawnOneToSettle();
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
    const std::size_t before = pacer_.wakeups();
    glfwWaitEventsTimeout(left);
    if (pacer_.wakeups() != before) {
      pacer_.woken(Clock::now());
    } else if (!steady) {
      autosave();  // idle: its clock still runs
    }
  }
  glfwPollEvents();
}

}  // namespace galsculpt
