// What the window shows of one simulation frame: the surface ready to upload, the anchors, the
// overlay's figures and a copy of the surface for the cursor's picks. The frame's worker thread
// builds it right after the frame (so the surface is rebuilt off the window's thread), and the
// window draws and reads it until the next one arrives: while a frame is in flight the window
// never touches the session, and what the overlay says is what is on the screen.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "app/render/render_mesh.h"
#include "engine/session/sculpt_session.h"

namespace galsculpt {

struct FrameView {
  bool valid = false;  // false until a session's first view
  FrameMetrics metrics;
  RenderMesh mesh;
  TriMesh surface;            // the drawn surface, for the brush cursor's picks
  std::vector<Vec3> anchors;  // anchored vertices' positions (nAnchored)
  std::string backendName;
  std::vector<std::string> notes;
  std::size_t historyBytes = 0, recordedEvents = 0;
  double msSurface = 0.0;  // rebuilding the surface (ms)
  double msView = 0.0;     // the whole view, surface included (ms)
  // When the worker finished the frame and its view: the next frame could start from then.
  std::chrono::steady_clock::time_point readyAt{};
  std::uint64_t generation = 0, damageRevision = 0;
  SurfaceStyle style;  // as drawn (the stress view's hottest value filled in)
};

// The view of the session's current state. Reads the session only: call it where no frame runs.
FrameView makeFrameView(const SculptSession& session, SurfaceStyle style,
                        const FrameMetrics& metrics);

// Whether `view` still shows the session's state in `style` (same frame, damage and colours).
bool viewIsCurrent(const FrameView& view, const SculptSession& session, const SurfaceStyle& style);

}  // namespace galsculpt
