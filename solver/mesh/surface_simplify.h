// Surface simplification by quadric-error edge collapses (Garland & Heckbert 1997).
//
// Used before meshing when a surface is finer than the requested tet count allows (a scanned
// model with 75k triangles meshed to 20k tets). Keeps a closed 2-manifold closed and manifold:
// a collapse is refused when it would break the link condition, flip or sliver a face, or
// leave a vertex with fewer than three faces.
#pragma once

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// Collapses edges until at most `targetFaces` faces remain (or no valid collapse is left).
// The input must be a closed, consistently oriented 2-manifold.
TriMesh simplifySurface(const TriMesh& mesh, int targetFaces);

}  // namespace galsculpt
