#include "app/window/sculpt_app.h"

#include <cstdio>
#include <stdexcept>

#include "engine/session/project_file.h"
#include "engine/surface/surface_io.h"

namespace galsculpt {

namespace fs = std::filesystem;

void SculptApp::execute(const Command& command) {
  const std::string& argument = command.argument;
  // Without a path, a file command asks for one.
  if (takesPath(command.kind) && argument.empty()) {
    if (command.kind == AppCommand::Open || session_) panels_.askPath(command.kind);
    return;
  }
  if (applyAtOnce(command)) return;
  if (stepInFlight()) {
    // The rest acts between frames: it waits with the input for the frame in flight, in order,
    // and the window keeps drawing meanwhile.
    InputEvent e;
    e.kind = InputEvent::Kind::Command;
    e.command = command;
    enqueue(e);
    return;
  }
  try {
    if (!applyToTools(command)) applyToSession(command);
  } catch (const std::exception& e) {
    const char* name = scriptCommandName(command.kind);
    fail(std::string(name ? name : "command") + " " + argument + ": " + e.what());
  }
}

// What needs no session and no pause of the frame in flight: play, camera, view toggles.
bool SculptApp::applyAtOnce(const Command& command) {
  const std::string& argument = command.argument;
  switch (command.kind) {
    case AppCommand::TogglePlay:
      playing_ = !playing_;
      return true;
    case AppCommand::Play:
      playing_ = true;
      return true;
    case AppCommand::Pause:
      playing_ = false;
      return true;
    case AppCommand::Step:
      stepOnce_ = true;
      return true;
    case AppCommand::Quit:
      glfwSetWindowShouldClose(window_, 1);
      return true;
    case AppCommand::ViewFront:
      camera_.viewFront();
      return true;
    case AppCommand::ViewSide:
      camera_.viewSide();
      return true;
    case AppCommand::ViewTop:
      camera_.viewTop();
      return true;
    case AppCommand::ToggleWireframe:
      wireframe_ = !wireframe_;
      return true;
    case AppCommand::ToggleCrackTint:
      style_.tintCracks = !style_.tintCracks;
      return true;
    case AppCommand::CycleView:
      style_.view = static_cast<SurfaceView>((static_cast<int>(style_.view) + 1) % 3);
      return true;
    case AppCommand::ScaleRadius:
      toolSettings_.radius *= std::stod(argument);
      return true;
    case AppCommand::ScaleStrength:
      toolSettings_.strength *= std::stod(argument);
      return true;
    case AppCommand::ToggleSymmetry:
      toolSettings_.symmetry = !toolSettings_.symmetry;
      return true;
    case AppCommand::Screenshot:
      presenter_.screenshotNext(argument);  // what this window frame draws, panels included
      return true;
    default:
      return false;
  }
}

// Files to open, tools, the surface's view, screenshots. False: a session command.
bool SculptApp::applyToTools(const Command& command) {
  const std::string& argument = command.argument;
  switch (command.kind) {
    case AppCommand::Open:
      opener_.start(argument, options_.solver);
      return true;
    case AppCommand::Recover: {  // as the Recover button of the crash-recovery offer
      const std::vector<fs::path> orphans = recovery_->orphans();
      if (orphans.empty()) throw std::runtime_error("nothing to recover");
      opener_.start(orphans.front(), options_.solver);
      return true;
    }
    case AppCommand::View:
      style_.view = argument == "damage"   ? SurfaceView::Damage
                    : argument == "stress" ? SurfaceView::Stress
                                           : SurfaceView::Shaded;
      return true;
    case AppCommand::Tool:
      if (controller_ && controller_->strokeActive()) return true;  // a stroke keeps its tool
      for (const ToolRow& row : toolTable())  // (the window's label or the script's name)
        if (argument == row.label || argument == row.name) {
          toolSettings_.tool = row.tool;
          return true;
        }
      throw std::runtime_error("unknown tool '" + argument + "'");
    case AppCommand::Radius:
      toolSettings_.radius = std::stod(argument);
      return true;
    case AppCommand::Strength:
      toolSettings_.strength = std::stod(argument);
      return true;
    case AppCommand::Symmetry:
      toolSettings_.symmetry = argument != "off";
      if (toolSettings_.symmetry)
        toolSettings_.symmetryAxis = argument == "y" ? 1 : argument == "z" ? 2 : 0;
      return true;
    default:
      return false;
  }
}

// What acts on the open session: saving, exporting, history, scene settings, framing.
void SculptApp::applyToSession(const Command& command) {
  const std::string& argument = command.argument;
  if (!session_) throw std::runtime_error("nothing is open");
  // A file or a history step holds whole actions: a stroke still held ends here.
  const AppCommand k = command.kind;
  if (k == AppCommand::SaveProject || k == AppCommand::SaveRecording || k == AppCommand::Undo ||
      k == AppCommand::Redo || k == AppCommand::Reset)
    controller_->cancelStroke();
  switch (command.kind) {
    case AppCommand::SaveProject:
      writeProject(argument, *session_, camera_.pose());
      projectFile_ = argument;
      session_->markSaved();
      report("saved project " + argument);
      break;
    case AppCommand::SaveRecording:
      session_->saveRecording(argument);
      report("saved recording " + argument + " (" + std::to_string(session_->recording().size()) +
             " events, " + std::to_string(session_->simulation().frame()) + " frames)");
      break;
    case AppCommand::Export: {
      const ExportedSurface exported = session_->simulation().exportSurface();
      writeVisualSurface(argument, exported.surface);
      report("exported surface " + argument + ": " + exported.summary());
    } break;
    case AppCommand::ExportTets: {
      const int leftOut = session_->simulation().writeTetsWithDamage(argument);
      report("exported tets " + argument + ".node/.ele/.face/.damage/.vtk" +
             (leftOut > 0 ? " (" + std::to_string(leftOut) +
                                " tet(s) parted between pieces and crushed flat left out)"
                          : std::string()));
    } break;
    case AppCommand::Undo:
      session_->undo();
      break;
    case AppCommand::Redo:
      session_->redo();
      break;
    case AppCommand::Reset:
      session_->reset();
      break;
    case AppCommand::Preset:  // as the Scene settings panel: edit, then apply
      panels_.editing().material = materialPreset(argument);
      applySceneSettings();
      break;
    case AppCommand::Grid:
      panels_.editing().solver.grid = argument;
      applySceneSettings();
      break;
    case AppCommand::FrameAll:
      camera_.frame(boundingBox(session_->simulation().state().x));
      break;
    case AppCommand::FramePiece:
      frameHoveredPiece();
      break;
    default:
      break;
  }
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
  try {
    SceneSettings s = panels_.editing();
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

}  // namespace galsculpt
