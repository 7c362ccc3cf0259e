// Scripted tools, headless: a playback script is a scene plus timed tool events (knife
// strokes, brush drags, anchor changes). `galsculpt play` runs one; the app records the same
// format. The format is documented in docs/scripts.md.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "engine/simulation.h"

namespace galsculpt {

struct ToolEvent {
  enum class Tool { Knife, Brush, Anchor };
  Tool tool = Tool::Knife;
  int frame = 0;     // acts on the frames after this one (0: from the start)
  int duration = 1;  // frames it lasts (knife sweep, brush drag)
  std::string path;  // JSON path, for messages
  // Knife: the blade segment at the start and at the end of the stroke.
  Vec3 from0 = Vec3::Zero(), from1 = Vec3::Zero(), to0 = Vec3::Zero(), to1 = Vec3::Zero();
  // Brush: grabs the vertices within radius of center (current positions) and drags them by
  // offset over the duration; released at the end unless hold is set.
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
  Vec3 offset = Vec3::Zero();
  bool hold = false;
  // Anchor: add (shape, fixed where the vertices are) or remove (by name or scene index).
  bool add = true;
  std::string name;
  AnchorDesc shape;
  int sceneAnchor = -1;
};

struct PlaybackScript {
  std::filesystem::path file;
  SceneDescription scene;
  int frames = 0;
  std::vector<ToolEvent> events;  // in frame order (stable)
};

// Reads and validates a script (and its scene); throws InputError naming file and JSON path.
PlaybackScript loadPlaybackScript(const std::filesystem::path& file);

class Playback {
 public:
  // Checks every anchor event's selection up front (InputError naming its JSON path).
  Playback(const PlaybackScript& script, Simulation& sim);
  // Applies the tools due for the next frame, then steps it.
  FrameMetrics advance();
  bool finished() const { return sim_.frame() >= script_.frames; }

 private:
  void apply(const ToolEvent& e, int step);

  const PlaybackScript& script_;
  Simulation& sim_;
  std::map<std::string, int> namedAnchors_;
  std::vector<std::pair<int, int>> releases_;  // (frame, anchor id) for brushes
};

}  // namespace galsculpt
