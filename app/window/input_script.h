// Synthetic input for the UI test and for demos: a JSON list of steps fed to the app's window
// through the same handlers as GLFW's events (`galsculpt open FILE --input-script STEPS.json`).
// Documented in docs/user-guide.md ("Scripted input"). Positions are fractions of the window
// (0..1 from the top left), so a script works at any window size.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/window/app_command.h"
#include "app/window/tool_controller.h"

namespace galsculpt {

struct InputStep {
  enum class Kind { Wait, WaitFrames, Move, Press, Release, Scroll, Key, Command };
  Kind kind = Kind::Wait;
  int frames = 1;  // Wait: window frames to let pass; WaitFrames: simulation frames to see drawn
  std::vector<std::pair<double, double>> points;  // Move: cursor samples within one frame
  MouseButton button = MouseButton::Left;
  bool shift = false, ctrl = false;
  double scroll = 0.0;
  int key = 0;  // Key: 'A'..'Z', '0'..'9', ' ', '[', ']', '.', or kKeyEscape
  AppCommand command = AppCommand::Play;  // Command (app_command.h: the names scripts use)
  std::string argument;
  std::string jsonPath;  // for messages
};

constexpr int kKeyEscape = 256;

struct InputScript {
  std::vector<InputStep> steps;
  // false: each frame waits for its simulation step (frame counts are exact, for tests);
  // true: the simulation runs on its worker thread as with a user at the mouse.
  bool realtime = false;
};

// Throws InputError naming the file and the JSON path of a bad step.
InputScript loadInputScript(const std::filesystem::path& file);

// Where a window's input script stands: the next step, and the wait a step asked for. The
// window asks once a window frame what to do.
class InputScriptRunner {
 public:
  void load(InputScript script) {
    script_ = std::move(script);
    active_ = true;
  }
  bool active() const { return active_; }
  // Frames run on the worker as with a user (the script's "realtime").
  bool realtime() const { return active_ && script_.realtime; }

  struct Turn {
    enum class Kind { Hold, Act, Done } kind = Kind::Hold;
    const InputStep* step = nullptr;  // Act: the step to act on
  };
  // This window frame's turn: Hold while a wait lasts, Done after the last step, else the next
  // step to act on (waits are the runner's own). `viewsShown`: views of finished frames drawn
  // so far (what "wait_frames" waits for in real time); `inputNotYetShown`: a screenshot waits
  // until what the steps before it did is on the screen.
  Turn next(int viewsShown, bool inputNotYetShown);

 private:
  InputScript script_;
  bool active_ = false;
  size_t next_ = 0;
  int wait_ = 0;        // window frames still to wait
  int waitViews_ = -1;  // "wait_frames" in real time: wait until viewsShown reaches it
};

}  // namespace galsculpt
