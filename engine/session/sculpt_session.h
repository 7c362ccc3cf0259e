// What one sculpting session holds beyond the simulation: the tools, the recording of every
// action as a playback script, and undo / redo.
//
// Every action goes through here so that it is applied, recorded and undoable in one place:
// the recording is always the script that replays the current state from the scene's start
// (an undone action's events leave it; a redone action's come back), and undo restores the
// state before the action exactly (SimulationSnapshot). History is bounded by a memory budget:
// the oldest steps are forgotten first.
#pragma once

#include <cstddef>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/session/playback.h"
#include "engine/session/simulation.h"

namespace galsculpt {

class SculptSession {
 public:
  SculptSession(const SceneDescription& scene, const TetMesh& mesh);

  Simulation& simulation() { return *sim_; }
  const Simulation& simulation() const { return *sim_; }
  const SceneDescription& scene() const { return scene_; }
  // The scene was edited in the app (scene_edit.h): a saved recording then brings its scene
  // along (RECORDING.scene.json beside it), since the scene file no longer describes it.
  void markSceneEdited() { sceneEdited_ = true; }

  // Starts an undoable action (a stroke from press to release, a reset): the state now is
  // what undo returns to. Ends a brush stroke still held.
  void beginAction(const std::string& label);

  // Tools; each is applied at once and recorded at the current frame.
  int knife(const Vec3& from0, const Vec3& from1, const Vec3& to0, const Vec3& to1,
            const Symmetry& symmetry);
  void beginStroke(const BrushStroke& stroke);
  void moveStroke(const Vec3& center, const Vec3& normal);
  void endStroke();
  bool strokeActive() const { return strokeEvent_ >= 0; }
  int paint(const Vec3& center, double radius, int seed, bool erase, const Symmetry& symmetry);
  // A playback script's event (docs/scripts.md), acting from the next frame on as it would in
  // the script: an undoable action, recorded. After an undo or redo, such events of the
  // recording that have not finished act on as a replay would (a brush drag under way lets go
  // at its end: its release frame is part of the state, AnchorRegistry::add). Checked first as
  // a script's events are (InputError naming `source` and the event's path; nothing recorded):
  // its seed and anchor selection against the mesh, a scene anchor it removes against the scene,
  // a named anchor it removes against those that hold or are to be added.
  void apply(ToolEvent event, const std::string& source = "apply");
  // The view, recorded once per frame (the last pose of each frame).
  void setCamera(const CameraPose& pose);

  // One frame: script brushes let go, held brushes act, the solver steps.
  FrameMetrics step();
  // Applied events that acted on nothing since the last call (ToolApplier::takeIdleReports).
  std::vector<std::string> takeIdleReports() { return tools_->takeIdleReports(); }

  // Back to the scene's start, as an undoable action.
  void reset();
  // Sets positions and/or velocities (null: kept; Simulation::setPositionsAndVelocities) as an
  // undoable action. It is not a tool event: the recording replays the tools alone, and a
  // project saved after it keeps the state set.
  void setState(const std::vector<Vec3>* x, const std::vector<Vec3>* v);
  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  const std::string& undoLabel() const;
  const std::string& redoLabel() const;
  bool undo();
  bool redo();
  std::size_t historyBytes() const { return historyBytes_; }
  void setHistoryBudget(std::size_t bytes);

  // The recording: events in the order they were applied.
  const std::vector<ToolEvent>& recording() const { return recording_; }
  // The recording with a stroke still held ending now (what files store; the app ends the
  // stroke before it saves, so that the saved state and the recording agree).
  std::vector<ToolEvent> recordingSoFar() const;
  // Writes it as a playback script of the frames run so far (docs/scripts.md).
  void saveRecording(const std::filesystem::path& file) const;
  // Runs a playback script from the scene's start (a fresh session of its scene) and keeps its
  // events as the recording, so sculpting goes on from where the script ends; `progress` gets
  // each frame. Throws InputError for anchors that select nothing (as `play` does).
  void replay(const PlaybackScript& script, const std::function<void(int, int)>& progress = {});
  // A project reopened: its state and recording replace the current ones (history cleared).
  void load(const SimulationSnapshot& state, std::vector<ToolEvent> recording);
  // Whether anything changed since the last markSaved (for autosave and the title bar).
  bool dirty() const { return dirty_; }
  void markSaved() { dirty_ = false; }

 private:
  // One undo or redo entry: the state to go to, and the recording there: the current one
  // cut to `keep` events, then `append`. Going there gives the entry that comes back.
  struct Step {
    std::string label;
    SimulationSnapshot state;
    std::size_t keep = 0;
    std::vector<ToolEvent> append;
    std::size_t bytes() const { return state.bytes() + append.size() * sizeof(ToolEvent); }
  };
  Step travel(Step target);
  bool moveAcross(std::deque<Step>& from, std::deque<Step>& to);
  void record(ToolEvent e);
  void trimHistory();

  SceneDescription scene_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<ToolApplier> tools_;
  SimulationSnapshot initial_;
  std::vector<ToolEvent> recording_;
  std::vector<ToolEvent> acting_;  // events given to apply() whose effect may still run
  int strokeEvent_ = -1;           // index of the open stroke's event in recording_
  std::deque<Step> undo_, redo_;
  std::size_t historyBytes_ = 0, historyBudget_ = std::size_t(1) << 30;
  bool dirty_ = false;
  bool sceneEdited_ = false;
};

}  // namespace galsculpt
