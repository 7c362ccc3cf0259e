#include "solver/mesh/mesh_stats.h"

#include <algorithm>

#include "solver/mesh/surface_checks.h"

namespace galsculpt {

TetMeshStats computeStats(const TetMesh& mesh) {
  TetMeshStats s;
  s.vertices = mesh.numVertices();
  s.tets = mesh.numTets();
  s.edges = static_cast<int>(uniqueEdges(mesh).size());
  s.box = boundingBox(mesh.vertices);
  s.volume = totalVolume(mesh);
  s.minQuality = mesh.tets.empty() ? 0.0 : 1.0;
  double sum = 0.0;
  for (const Tet& t : mesh.tets) {
    const auto& v = mesh.vertices;
    const double q = tetMeanRatio(v[t[0]], v[t[1]], v[t[2]], v[t[3]]);
    s.minQuality = std::min(s.minQuality, q);
    sum += q;
    s.qualityHistogram[std::clamp(static_cast<int>(q * 10.0), 0, 9)]++;
  }
  s.meanQuality = mesh.tets.empty() ? 0.0 : sum / mesh.numTets();
  const TriMesh boundary = boundarySurface(mesh);
  s.boundaryFaces = boundary.numFaces();
  const SurfaceTopology topo = analyzeSurface(boundary);
  s.watertight = topo.closedManifold() && !boundary.faces.empty();
  s.boundaryProblem = topo.describeProblem();
  s.pieces = countPieces(mesh);
  return s;
}

}  // namespace galsculpt
