// Checks on triangle surfaces: closedness, manifoldness, orientation, self-intersection, volume.
//
// Used before tetrahedralization (TetGen aborts on bad input; we say what is wrong first) and
// by the watertightness tests of the visualization surface.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct SurfaceTopology {
  int boundaryEdges = 0;        // edges with one face: the surface is open
  int nonManifoldEdges = 0;     // edges with three or more faces
  int inconsistentEdges = 0;    // edges whose two faces traverse them the same way
  int nonManifoldVertices = 0;  // vertices whose faces form more than one fan
  int degenerateFaces = 0;      // repeated vertex or zero area
  int pieces = 0;               // connected components (over shared vertices)
  Edge firstBoundaryEdge{-1, -1};
  Edge firstNonManifoldEdge{-1, -1};

  bool closedManifold() const {
    return boundaryEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0 &&
           nonManifoldVertices == 0 && degenerateFaces == 0;
  }
  // One sentence naming the first problem ("open: ..."), empty when closedManifold().
  std::string describeProblem() const;
};

SurfaceTopology analyzeSurface(const TriMesh& mesh);

// Signed enclosed volume (divergence theorem): positive for a closed, outward-oriented surface.
double enclosedVolume(const TriMesh& mesh);
double surfaceArea(const TriMesh& mesh);
// The signed volume each group of faces encloses (`groupOfFace`: a label in [0, groups) per
// face, e.g. countSurfacePieces' shells).
std::vector<double> enclosedVolumes(const TriMesh& mesh, const std::vector<int>& groupOfFace,
                                    int groups);

// Pairs of faces that cross each other (faces sharing an edge are not tested; touching is not
// crossing), in increasing order. Stops after `maxPairs`. With `faceMask` (nFaces), only pairs
// with at least one face marked are tested: after moving some vertices, the pairs that may have
// changed.
std::vector<std::pair<int, int>> findSelfIntersections(const TriMesh& mesh, size_t maxPairs = 16,
                                                       const std::vector<char>* faceMask = nullptr);

// Connected components over shared vertices; fills `pieceOfFace` when given.
int countSurfacePieces(const TriMesh& mesh, std::vector<int>* pieceOfFace = nullptr);

}  // namespace galsculpt
