// GPU-ready triangle data: positions, smooth normals and colours, flattened to floats.
#pragma once

#include <vector>

#include "solver/tet_mesh.h"

namespace galsculpt {

struct RenderMesh {
  std::vector<float> positions;   // (3 nVerts)
  std::vector<float> normals;     // (3 nVerts)
  std::vector<float> colors;      // (3 nVerts), linear RGB
  std::vector<unsigned> indices;  // (3 nTris)
};

RenderMesh makeRenderMesh(const TriMesh& mesh, const Vec3& color);

}  // namespace galsculpt
