#include "app/window/frame_view.h"

#include <algorithm>

#include "solver/frame/timing.h"

namespace galsculpt {

FrameView makeFrameView(const SculptSession& session, SurfaceStyle style,
                        const FrameMetrics& metrics) {
  const auto start = Clock::now();
  const Simulation& sim = session.simulation();
  FrameView view;
  view.valid = true;
  view.metrics = metrics;
  const VisualSurface& surface = sim.surface();
  view.msSurface = msSince(start);
  std::vector<double> values;
  if (style.view == SurfaceView::Damage) {
    values = sim.vertexDamage();
    style.scaleMax = 1.0;
  } else if (style.view == SurfaceView::Stress) {
    values = sim.vertexStress();
    // The hottest colour at the 98th percentile: a few peaks do not wash the rest out.
    std::vector<double> sorted = values;
    const size_t k = sorted.size() * 98 / 100;
    if (!sorted.empty()) {
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
      style.scaleMax = std::max(sorted[k], 1e-9);
    }
  }
  view.mesh = makeRenderMesh(surface, style, values);
  view.surface = surface.mesh;
  for (int v : sim.anchors().heldVertices()) view.anchors.push_back(sim.state().x[v]);
  view.backendName = sim.backendName();
  view.notes = sim.notes();
  view.historyBytes = session.historyBytes();
  view.recordedEvents = session.recording().size();
  view.generation = sim.generation();
  view.damageRevision = sim.state().damageRevision;
  view.style = style;
  view.msView = msSince(start);
  return view;
}

bool viewIsCurrent(const FrameView& view, const SculptSession& session, const SurfaceStyle& style) {
  const Simulation& sim = session.simulation();
  return view.valid && view.generation == sim.generation() &&
         view.damageRevision == sim.state().damageRevision && view.style.view == style.view &&
         view.style.tintCracks == style.tintCracks;
}

}  // namespace galsculpt
