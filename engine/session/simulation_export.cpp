// Simulation::exportSurface: the visualization surface made into what an export promises.
#include <algorithm>

#include "engine/session/simulation.h"
#include "solver/io/atomic_file.h"
#include "solver/io/damage_io.h"
#include "solver/io/tetgen_io.h"
#include "solver/io/vtk_io.h"

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
  std::vector<int> piece = pieces_.ofVertices();
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
  ExportedSurface out = sealedEdges == 0
                            ? makeExportSurface(surface_.builder().surface(),
                                                surface_.builder().heldCentres(state_), piece)
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

namespace {

// Removes the vertices no tet uses, the others keeping their order; returns each kept vertex's
// index before.
std::vector<int> dropUnusedVertices(TetMesh& mesh) {
  std::vector<int> number(mesh.numVertices(), -1);
  for (const Tet& t : mesh.tets)
    for (int v : t) number[v] = 0;
  std::vector<int> original;
  std::vector<Vec3> vertices;
  for (int v = 0; v < mesh.numVertices(); ++v) {
    if (number[v] < 0) continue;
    number[v] = static_cast<int>(original.size());
    original.push_back(v);
    vertices.push_back(mesh.vertices[v]);
  }
  mesh.vertices = std::move(vertices);
  for (Tet& t : mesh.tets)
    for (int& v : t) v = number[v];
  return original;
}

}  // namespace

int Simulation::writeTetsWithDamage(const std::filesystem::path& stem) const {
  TetMesh now = model_.mesh;
  now.vertices = state_.x;
  // A tet parted between pieces carries nothing between them and may have been crushed flat
  // as they moved; a mesh reader refuses a zero-volume tet, so such tets are left out of the
  // set (their edges' damage with them). A flat tet of one piece is written as it is.
  TetMesh kept = now;
  kept.tets.clear();
  for (const Tet& t : now.tets) {
    const bool parted = pieces_.of(t[0]) != pieces_.of(t[1]) ||
                        pieces_.of(t[0]) != pieces_.of(t[2]) ||
                        pieces_.of(t[0]) != pieces_.of(t[3]);
    if (!parted ||
        !isFlatTet(now.vertices[t[0]], now.vertices[t[1]], now.vertices[t[2]], now.vertices[t[3]]))
      kept.tets.push_back(t);
  }
  const int leftOut = now.numTets() - kept.numTets();
  std::vector<Edge> edges = model_.edges;
  std::vector<std::uint8_t> damaged = state_.damaged;
  std::vector<float> crossing = state_.crossing;
  if (leftOut > 0) {
    // Vertices of left-out tets alone go too (a vertex in no tet has no mass).
    const std::vector<int> original = dropUnusedVertices(kept);
    edges = uniqueEdges(kept);
    damaged.assign(edges.size(), 0);
    crossing.assign(edges.size(), kNoCrossing);
    for (size_t e = 0; e < edges.size(); ++e) {
      Edge was{original[edges[e][0]], original[edges[e][1]]};
      if (was[0] > was[1]) std::swap(was[0], was[1]);
      const size_t at =
          std::lower_bound(model_.edges.begin(), model_.edges.end(), was) - model_.edges.begin();
      damaged[e] = state_.damaged[at];
      crossing[e] = state_.crossing[at];
    }
  }
  // The mesh and its damage are one set: committed together, stamped alike.
  FileSet set;
  addTetGen(set, stem, kept);
  addDamage(set, stem.string() + ".damage", edges, damaged, crossing);
  set.commit();
  // Piece of each tet: numbered in tet order when all four corners share it, otherwise -1.
  std::vector<int> label(model_.numVertices(), -1);
  int pieces = 0;
  VtkCellField piece{"piece", std::vector<double>(model_.numTets(), -1.0)};
  for (int t = 0; t < model_.numTets(); ++t) {
    if (!pieces_.counted(t)) continue;
    int& id = label[pieces_.of(model_.mesh.tets[t][0])];
    if (id < 0) id = pieces++;
    piece.values[t] = id;
  }
  writeVtk(stem.string() + ".vtk", now,
           {{"damage", tetDamageFraction(model_.tetEdges, state_.damaged)}, piece});
  return leftOut;
}

}  // namespace galsculpt
