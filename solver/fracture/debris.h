// Pieces and debris. A piece is a part of the body joined by undamaged edges (a vertex whose
// edges are all damaged is a piece of its own). Its rest volume is that of its vertices' corner
// cells: a quarter of every tet around each of its vertices, which is what its closed surface
// encloses at rest (docs/surface.md). Its material is its whole tets (all four corners in it):
// only they hold its shape, the tets it shares with other pieces hold nothing but edge lengths.
// Debris is a piece whose material is under a fraction of the body's rest volume. That includes
// the sliver, a piece with no whole tet, which edge lengths alone let turn inside out whatever
// its size, and the crushed clump whose corner cells are large beside its few whole tets (a
// 6-vertex clump holding 2 whole tets, 0.13 % of a ball, counted 2 % by its corner cells, was
// crushed inside out by the pieces around it).
//
// The debris rule (scene: fracture.debris, docs/physics.md): debris is removed from the
// simulation. Damage only grows, so a piece only ever splits and debris stays debris: what is
// removed is a function of the damage alone, the same for every executor, after an undo and in
// a reopened project, and needs no state of its own.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/model/sim_model.h"

namespace galsculpt {

struct PieceCensus {
  int pieces = 0;
  std::vector<int> pieceOfVertex;     // (nVerts) compact: 0 .. pieces - 1, in first-vertex order
  std::vector<double> restVolume;     // (pieces) m^3
  std::vector<int> vertexCount;       // (pieces)
  std::vector<int> wholeTets;         // (pieces) tets with all four corners in the piece
  std::vector<double> wholeVolume;    // (pieces) m^3, their rest volume: the piece's material
  std::vector<std::uint8_t> isWhole;  // (tets) 1 when all four corners lie in one piece
  double bodyRestVolume = 0.0;        // every tet's, damaged or not
  double wholeRestVolume = 0.0;       // the whole tets' (what the pieces' material fills)
};

PieceCensus censusPieces(const SimModel& model, const std::vector<std::uint8_t>& damaged);

// 1 for each piece whose whole tets are under `fraction` of the body's rest volume (none for
// fraction 0).
std::vector<std::uint8_t> debrisPieces(const PieceCensus& census, double fraction);

// 1 for each vertex of a debris piece; empty when there is none (the common case costs no
// per-vertex test downstream).
std::vector<std::uint8_t> debrisVertices(const PieceCensus& census, double fraction);

}  // namespace galsculpt
