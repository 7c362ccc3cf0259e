// Simulation::exportSurface: the visualization surface made into what an export promises.
#include <algorithm>

#include "engine/session/simulation.h"

namespace galsculpt {

namespace {

// A damaged edge inside one piece whose ends stand no further apart than this, relative to its
// rest length, is a closed slit: the export seals it (docs/surface.md, "Exports").
constexpr double kClosedSlitStretch = 1.1;
// Rounds of carving out the corners of cells whose faces still cross (within kExportCarveBudget).
constexpr int kCarveRounds = 8;

}  // namespace

ExportedSurface Simulation::exportSurface() const {
  surface();  // brings the builder up to the current state
  std::vector<int> piece = pieceNumber_;
  std::vector<int> removedPieces;
  for (int v = 0; v < model_.numVertices(); ++v) {
    if (!removed(v)) continue;
    removedPieces.push_back(piece[v]);
    piece[v] = -1;
  }
  std::sort(removedPieces.begin(), removedPieces.end());
  removedPieces.erase(std::unique(removedPieces.begin(), removedPieces.end()), removedPieces.end());

  // Closed slits sealed: the same pieces, without the cracks that part nothing and stand closed.
  SimState sealed;
  sealed.x = state_.x;
  sealed.damaged = state_.damaged;
  sealed.crossing = state_.crossing;
  int sealedEdges = 0;
  for (int e = 0; e < model_.numEdges(); ++e) {
    const auto [a, b] = model_.edges[e];
    if (!sealed.damaged[e] || piece[a] != piece[b]) continue;
    const double now = (state_.x[a] - state_.x[b]).norm();
    const double rest = (model_.mesh.vertices[a] - model_.mesh.vertices[b]).norm();
    if (now > kClosedSlitStretch * rest) continue;
    sealed.damaged[e] = 0;
    sealed.crossing[e] = kNoCrossing;
    ++sealedEdges;
  }
  // The export of a state with other damage than the simulation's: a surface built for it.
  auto exportOf = [&](const SimState& state) {
    SurfaceBuilder builder(model_);
    builder.update(model_, state);
    return makeExportSurface(builder.surface(), builder.heldCentres(state), piece);
  };
  ExportedSurface out =
      sealedEdges == 0
          ? makeExportSurface(surfaceBuilder_.surface(), surfaceBuilder_.heldCentres(state_), piece)
          : exportOf(sealed);

  // Where faces still cross (a broken end's crack band folded through itself), the corners
  // whose cells bound them are carved out: every edge at them parted for the export, so each
  // becomes a shell of its own that the export leaves out as detached material, and the surface
  // is made again (docs/surface.md, "Exports").
  std::vector<char> carved(model_.numVertices(), 0);
  for (int round = 0; round < kCarveRounds && out.crossings > 0; ++round) {
    const std::vector<char> carvedBefore = carved;
    for (int v : out.crossingCells) carved[v] = 1;
    for (int e = 0; e < model_.numEdges(); ++e) {
      const auto [a, b] = model_.edges[e];
      if (carved[a] || carved[b]) sealed.damaged[e] = 1;
    }
    ExportedSurface next = exportOf(sealed);
    if (next.detachedVolume > kExportCarveBudget * (next.volume + next.detachedVolume)) {
      carved = carvedBefore;
      out.carveBudgetReached = true;
      break;
    }
    out = std::move(next);
  }
  // What carving could not clear within its budget: the pieces still folded through themselves
  // are remade as the boundary of the region they enclose.
  solidifyCrossingPieces(out, piece);
  out.sealedEdges = sealedEdges;
  out.removedPieces = static_cast<int>(removedPieces.size());
  out.carvedCorners = static_cast<int>(std::count(carved.begin(), carved.end(), 1));
  return out;
}

}  // namespace galsculpt
