// Scripted tools, headless: a playback script is a scene plus timed tool events (knife
// strokes, brush drags, anchor changes). `galsculpt play` runs one; the app records the same
// format. The format is documented in docs/scripts.md.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/session/sculptor.h"
#include "engine/session/simulation.h"

namespace galsculpt {

// Where the camera looks from (the app's orbit camera, without the app).
struct CameraPose {
  Vec3 target = Vec3::Zero();
  double distance = 1.0;
  double yaw = 0.6, pitch = 0.35;  // radians
};

// A brush stroke's later position (app strokes: one per frame the cursor moved).
struct StrokeKey {
  int frame = 0;
  Vec3 center = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();
};

// One event of a script or a recording. What a tool does with the mouse is a BrushStroke
// (sculptor.h: the tool, where, how wide, the piece, the mirror plane); an event holds one and
// adds when it acts and what else the kind of event needs.
struct ToolEvent {
  // Knife: a blade swept over `duration` frames. Drag: a script's fixed drag of what lies within
  // the radius by `offset` ("brush" in scripts). Anchor: an anchor added by shape or removed.
  // Stroke: a brush of the tool table following `moves` (what the app records). Paint: anchor
  // paint or erase. Camera: the view (no effect on the physics).
  enum class Kind { Knife, Drag, Anchor, Stroke, Paint, Camera };
  Kind kind = Kind::Knife;
  int frame = 0;     // acts on the frames after this one (0: from the start)
  int duration = 1;  // frames it lasts (knife sweep, drag)
  std::string path;  // JSON path, for messages
  // The tool and where it acts: stroke.kind is the tool (Knife, a brush, AnchorPaint or
  // AnchorErase); center, radius and seed for strokes, paint and drags; symmetry for the knife,
  // strokes and paint; normal and strength for brushes.
  BrushStroke stroke;
  // Knife: the blade segment at the start and at the end of the stroke.
  Vec3 from0 = Vec3::Zero(), from1 = Vec3::Zero(), to0 = Vec3::Zero(), to1 = Vec3::Zero();
  // Drag: moves the vertices within the radius by offset over the duration; released at the
  // end unless hold is set.
  Vec3 offset = Vec3::Zero();
  bool hold = false;
  // Anchor: add (shape, fixed where the vertices are) or remove (by name or scene index).
  bool add = true;
  std::string name;
  AnchorDesc shape;
  int sceneAnchor = -1;
  // Stroke: its moves; it ends (lets go) before frame `end` + 1.
  std::vector<StrokeKey> moves;
  int end = 0;
  CameraPose camera;
  nlohmann::json source;  // the event as read from a file (anchor events are written back so)
  // Given to a session as a script's event (SculptSession::apply), not made by the app's tools:
  // it acts through the frames as in a script, also after an undo or redo lands before its end.
  bool scripted = false;

  bool erase() const { return stroke.kind == Tool::AnchorErase; }
};

struct PlaybackScript {
  std::filesystem::path file;
  SceneDescription scene;
  int frames = 0;
  std::vector<ToolEvent> events;  // in frame order (stable)
};

// Reads and validates a script (and its scene); throws InputError naming file and JSON path.
PlaybackScript loadPlaybackScript(const std::filesystem::path& file);
// The same for a script already parsed (`file` names it and anchors its scene's path).
PlaybackScript parsePlaybackScript(const nlohmann::json& root, const std::filesystem::path& file);

// Writes a script (the app's recording) atomically; the scene is referred to relative to the
// script's folder. Numbers keep every digit, so a replay is exact.
void writePlaybackScript(const std::filesystem::path& file, const std::filesystem::path& scene,
                         int frames, const std::vector<ToolEvent>& events);
nlohmann::json toolEventJson(const ToolEvent& e);
// A camera pose as scripts and projects hold it: target, distance, yaw, pitch.
nlohmann::json cameraPoseJson(const CameraPose& pose);
CameraPose readCameraPose(JsonObject& o);
// One event as a script holds it; throws InputError naming `file` and `path`.
ToolEvent parseToolEvent(const nlohmann::json& value, const std::string& path,
                         const std::string& file);

// Applies one event's effect due at `frame` (the frame about to be computed is frame + 1):
// the app calls it as the user acts, playback as the script says.
class ToolApplier {
 public:
  ToolApplier(Simulation& sim, std::string file)
      : sim_(sim), sculptor_(sim), file_(std::move(file)) {}
  // Everything due before frame + 1, in order: script brushes whose drag is over let go, the
  // events due apply, held brushes act. Playback, a replay into a session and the app's frames
  // all go through it, so they act alike.
  void prepareFrame(const std::vector<ToolEvent>& events, int frame);
  // One event's effect due at `frame`; returns the edges it cut (knife), else 0.
  int apply(const ToolEvent& e, int frame);
  // A script's end: the knife events recorded at its last frame (cuts made after the last
  // computed frame, which show in the state with no frame after them). Cutting is idempotent,
  // so a session that goes on and prepares that frame again changes nothing.
  void applyTrailing(const std::vector<ToolEvent>& events, int lastFrame);
  Sculptor& sculptor() { return sculptor_; }
  const std::optional<CameraPose>& camera() const { return camera_; }
  // What events acted on nothing since the last call, a line each: "frame 12: knife
  // ($.events[3]) crossed no edge: its blade passed 0.0022 m from the nearest vertex" (a knife
  // that cut no edge over its sweep, a brush, stroke or anchor paint that reached no vertex).
  std::vector<std::string> takeIdleReports() { return std::exchange(idle_, {}); }
  // How many of those there are (not taken).
  int idleCount() const { return static_cast<int>(idle_.size()); }

 private:
  void reportIdle(const ToolEvent& e, int frame, const std::string& what);
  // "the nearest is 0.0022 m from its centre (radius 0.01 m)"
  std::string nearestText(const Vec3& center, double radius) const;

  Simulation& sim_;
  Sculptor sculptor_;
  std::string file_;
  std::optional<CameraPose> camera_;
  std::map<std::string, int> knifeCuts_;  // per knife event under way: edges cut so far
  std::vector<std::string> idle_;
};

// Checks an event against the mesh: an anchor it adds selects something, a brush's or anchor
// paint's `seed` is a vertex (InputError naming `file` and the event's JSON path otherwise).
void checkToolEvent(const ToolEvent& event, const Simulation& sim, const std::string& file);
// checkToolEvent for every event of a script, up front.
void checkScriptAnchors(const PlaybackScript& script, const Simulation& sim);

class Playback {
 public:
  // Checks every anchor event's selection up front (InputError naming its JSON path).
  Playback(const PlaybackScript& script, Simulation& sim);
  // Applies the tools due for the next frame, then steps it; after the last frame, the cuts
  // recorded at it (ToolApplier::applyTrailing).
  FrameMetrics advance();
  bool finished() const { return sim_.frame() >= script_.frames; }
  // The script's latest camera event so far, if any.
  const std::optional<CameraPose>& camera() const { return tools_.camera(); }
  // ToolApplier::takeIdleReports: the events that acted on nothing since the last call.
  std::vector<std::string> takeIdleReports() { return tools_.takeIdleReports(); }

 private:
  const PlaybackScript& script_;
  Simulation& sim_;
  ToolApplier tools_;
};

}  // namespace galsculpt
