// The surface that leaves the app: one closed, outward-oriented shell per piece, checked.
//
// The visualization surface (surface_builder.h) is closed piece by piece, but it is made for the
// screen: a slit inside a piece is a zero-volume cavity shell of its own, and the two sides of a
// closed crack (halves at rest after a cut, a crack band) are placed by each side's own fitted
// deformation, so where they meet they may cross each other by a little. An export is a solid a
// user takes to other programs, so:
//   - each piece keeps only its outer shell (the one enclosing the most volume); the other
//     shells of the piece (internal cracks: slits and voids) are left out, counted, and the
//     volume they enclosed reported;
//   - every crack-side copy (a surface vertex that holds only some of its point's corners) is
//     pulled towards the mean of the corners it holds by `separation` of the way, so the two
//     sides of a closed crack stand apart (about 1 % of the local edge length at the default)
//     and never share a position;
//   - the result is checked for crossing faces; the crack-side copies of faces that still cross
//     are pulled further (doubling, up to `maxSeparation`) and the check repeated, so that what
//     is written is free of crossings wherever pulling crack faces in can make it so. What is
//     left is counted and reported: crossings inside a piece's shell apart from contact, faces
//     of two pieces that cross (pieces that overlap, which the simulation does not prevent).
// Simulation::exportSurface carves out the corners whose cells bound faces of one piece still
// crossing (a broken end's crack band folded through itself): each becomes a shell of its own,
// which the export leaves out as material detached from its piece, with its volume reported.
// Where carving would leave out too much (pieces folded through themselves in many places), the
// pieces still crossing are remade as the boundary of the region their faces wind around
// (solidify.h): closed and free of crossings, rounded off at the grid's cell, the change of
// volume reported.
// docs/surface.md ("Exports") states what an export promises.
#pragma once

#include <string>
#include <vector>

#include "engine/surface/surface_builder.h"

namespace galsculpt {

// The most of a body's volume that carving out folds may leave out (Simulation::exportSurface);
// past it the crossings are left in the file and said. A body whose pieces fold through
// themselves in many places (where several knife cuts meet) would otherwise lose a fifth.
constexpr double kExportCarveBudget = 0.03;

struct SurfaceExportOptions {
  double separation = 0.02;    // of the way from a crack-side copy to its held corners
  double maxSeparation = 0.5;  // the furthest a copy is pulled while faces still cross
  int rounds = 8;              // check-and-pull rounds
};

struct ExportedSurface {
  VisualSurface surface;  // faces of kept pieces' outer shells, compact numbering
  int pieces = 0;         // shells written: one per piece
  int removedPieces = 0;  // debris pieces the scene's rule removed: not written
  int sealedEdges = 0;    // closed slits inside pieces, sealed (Simulation::exportSurface)
  int carvedCorners = 0;  // mesh vertices carved out where faces crossed (ditto)
  bool carveBudgetReached = false;  // carving stopped: more would leave out too much volume
  int droppedShells = 0;            // internal crack shells (cavities) left out
  double droppedVolume = 0.0;       // the volume they enclosed (absolute, m^3)
  int detachedShells = 0;           // other shells of a piece enclosing material, left out
  double detachedVolume = 0.0;      // the material they held, m^3
  double volume = 0.0;              // the volume the written shells enclose, m^3
  int invertedShells = 0;           // pieces whose outer shell encloses no positive volume
  int pulledVertices = 0;           // crack-side copies pulled further than `separation`
  int crossings = 0;                // face pairs of one piece that still cross (self-intersection)
  std::vector<int> crossingCells;   // tet-mesh vertices whose cells bound those faces, sorted
  int contacts = 0;                 // face pairs of two pieces that cross (the pieces overlap)
  int solidifiedPieces = 0;         // pieces remade as the boundary of the region they enclose
  double solidifiedVolumeChange = 0.0;  // the volume that remaking added (< 0: removed), m^3
  // One line: "2 piece(s), closed; ..." for the command line and the window's messages.
  std::string summary() const;
};

// `all`: the builder's surface; `heldCentre`: SurfaceBuilder::heldCentres of the same state;
// `pieceOfVertex`: the piece of each tet-mesh vertex, negative for vertices whose faces are not
// exported (removed debris).
ExportedSurface makeExportSurface(const VisualSurface& all, const std::vector<Vec3>& heldCentre,
                                  const std::vector<int>& pieceOfVertex,
                                  const SurfaceExportOptions& options = {});

// Remakes every piece whose own faces still cross (`out.crossingCells`) as the boundary of the
// region its shell winds around (solidify.h, a grid of its median edge), keeping the
// largest shell that gives (other shells: detached material or cavities, counted as such), and
// counts the crossings again. A piece too thin for the grid keeps its faces.
void solidifyCrossingPieces(ExportedSurface& out, const std::vector<int>& pieceOfVertex);

}  // namespace galsculpt
