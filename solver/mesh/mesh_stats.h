// Summary figures of a tet mesh, as printed by `galsculpt mesh info`.
#pragma once

#include <array>
#include <string>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct TetMeshStats {
  int vertices = 0;
  int tets = 0;
  int edges = 0;
  int boundaryFaces = 0;
  BoundingBox box;
  double volume = 0.0;
  double minQuality = 0.0;  // mean-ratio quality, 1 = regular tet
  double meanQuality = 0.0;
  std::array<int, 10> qualityHistogram{};  // bins of width 0.1 over [0, 1]
  bool watertight = false;      // the boundary is a closed, consistently oriented 2-manifold
  std::string boundaryProblem;  // why not watertight
  int pieces = 0;
};

TetMeshStats computeStats(const TetMesh& mesh);

}  // namespace galsculpt
