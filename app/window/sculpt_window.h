// The sculpting application's window: GLFW + Dear ImGui over the shared renderer, running a
// SculptSession (simulation, tools, recording, undo) with panels, menus, a live overlay,
// autosave and crash recovery. docs/user-guide.md describes what the user sees.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "engine/scene/solver_options_json.h"

namespace galsculpt {

struct SculptWindowOptions {
  std::filesystem::path file;  // scene, project or mesh to open first
  int width = 1280, height = 800;
  // Synthetic input (app/window/input_script.h); the app closes when it has run out.
  std::optional<std::filesystem::path> inputScript;
  // Written when the window closes (the UI test reads them).
  std::optional<std::filesystem::path> saveProjectOnExit, saveRecordingOnExit;
  double autosaveSeconds = 60.0;  // 0: never
  bool offerRecovery = true;      // ask about files left by a crash
  bool startPlaying = true;
  SolverOverrides solver;  // set over every opened file's solver (--solver-option, --backend)
};

// Runs until the window closes; returns false (with a reason) when no window can be opened.
// `log` gets progress, errors and what was written.
bool runSculptWindow(const SculptWindowOptions& options, std::ostream& log, std::string* error);

}  // namespace galsculpt
