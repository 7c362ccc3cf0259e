// Simulation::exportSurface: the visualization surface made into what an export promises.
#include "engine/session/simulation.h"

namespace galsculpt {

namespace {

// A damaged edge inside one piece whose ends stand no further apart than this, relative to its
// rest length, is a closed slit: the export seals it (docs/surface.md, "Exports").
constexpr double kClosedSlitStretch = 1.1;

}  // namespace

ExportedSurface Simulation::exportSurface() const {
  surface();  // brings the builder up to the current state
  std::vector<int> piece = pieceNumber_;
  for (int v = 0; v < model_.numVertices(); ++v)
    if (removed(v)) piece[v] = -1;

  // Closed slits sealed: the same pieces, without the cracks that part nothing and stand closed.
  SimState sealed;
  sealed.x = state_.x;
  sealed.damaged = state_.damaged;
  sealed.crossing = state_.crossing;
  int sealedEdges = 0;
  for (int e = 0; e < model_.numEdges(); ++e) {
    if (!sealed.damaged[e]) continue;
    const auto [a, b] = model_.edges[e];
    if (piece[a] != piece[b]) continue;
    const double now = (state_.x[a] - state_.x[b]).norm();
    const double rest = (model_.mesh.vertices[a] - model_.mesh.vertices[b]).norm();
    if (now > kClosedSlitStretch * rest) continue;
    sealed.damaged[e] = 0;
    sealed.crossing[e] = kNoCrossing;
    ++sealedEdges;
  }
  ExportedSurface out;
  if (sealedEdges == 0) {
    out = makeExportSurface(surfaceBuilder_.surface(), surfaceBuilder_.heldCentres(state_), piece);
  } else {
    SurfaceBuilder builder(model_);
    builder.update(model_, sealed);
    out = makeExportSurface(builder.surface(), builder.heldCentres(sealed), piece);
  }
  out.sealedEdges = sealedEdges;
  return out;
}

}  // namespace galsculpt
