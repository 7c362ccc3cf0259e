// What the window can be asked to do, as typed commands shared by the menus, the keys, the
// panels' buttons and scripted input (docs/user-guide.md, "Scripted input"): each source builds
// a Command, one dispatcher (SculptApp::execute) acts on it. Names are parsed once, when a
// script is loaded; nothing dispatches by string.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace galsculpt {

enum class AppCommand {
  // Files. Without a path: ask for one (the path dialog).
  Open,
  SaveProject,
  SaveRecording,
  Export,
  ExportTets,
  Recover,  // open the newest autosave left by a crash
  // History and time.
  Undo,
  Redo,
  Reset,
  Play,
  Pause,
  TogglePlay,
  Step,
  // Tools (argument: a tool name, a length, "off"/"x"/"y"/"z").
  Tool,
  Radius,
  Strength,
  ScaleRadius,    // argument: the factor
  ScaleStrength,  // argument: the factor
  Symmetry,
  ToggleSymmetry,
  // Scene settings, as the Scene panel: edit, then restart.
  Preset,
  Grid,
  // View.
  View,  // argument: shaded, damage or stress
  CycleView,
  ToggleWireframe,
  ToggleCrackTint,
  FrameAll,
  FramePiece,  // the piece under the cursor
  ViewFront,
  ViewSide,
  ViewTop,
  Screenshot,  // argument: the PNG's path
  Quit,
};

struct Command {
  AppCommand kind = AppCommand::Play;
  std::string argument;
};

// The names scripts use ("save_project", ...); nullopt for an unknown name.
std::optional<AppCommand> scriptCommandNamed(std::string_view name);
// nullptr for the commands scripts do not name (toggles and keys' shortcuts).
const char* scriptCommandName(AppCommand command);
std::vector<std::string> scriptCommandNames();

// Whether the command needs a path and asks for one without it.
bool takesPath(AppCommand command);

// The key bindings (docs/user-guide.md): what a key press does, or nothing. `projectFile` is
// the open project, which Ctrl+S saves in place.
std::optional<Command> keyCommand(int key, bool ctrl, bool shift, const std::string& projectFile);

}  // namespace galsculpt
