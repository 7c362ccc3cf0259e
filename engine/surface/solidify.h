// The boundary of the solid a closed surface winds around, remade free of crossings.
//
// A closed, outward-oriented surface that passes through itself (a crack band folded through
// its piece, two sheets of one body overlapping) still bounds a region: the points it winds
// around at least once (generalized winding number >= 1/2). Its boundary is what a solid
// modeller, a slicer or TetGen needs. It is found on a grid:
//   - winding numbers at the grid's nodes, exactly, by sweeping each column of nodes along z
//     and counting the signed crossings of the surface's faces below each node (a face crossed
//     against its normal enters the solid: +1);
//   - the surface's unsigned distance at the nodes beside a change (SurfaceBvh::distance),
//     signed by the winding: a field whose zero level lies on the surface where the surface is
//     the region's boundary and nowhere inside it;
//   - marching tetrahedra over the grid's cubes (six tets each about the main diagonal, the
//     Freudenthal split, which neighbouring cubes share), one vertex per crossed grid edge at
//     the field's linear zero.
// The level set of a piecewise-linear field on a simplicial complex at a value no node takes is
// a closed 2-manifold, and each tet's triangles lie inside that tet: the result never crosses
// itself, whatever the input did. Features smaller than the grid's cell are rounded off.
#pragma once

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct SolidifyOptions {
  double cell = 0.0;             // grid spacing (m); must be positive
  long long maxNodes = 8000000;  // past this the cell grows until the grid fits
  // How near a grid node a vertex may sit, as a fraction of its grid edge: the surface's
  // crossing is moved to this bound where it falls nearer. It keeps the triangles' smallest
  // angles away from zero, which a mesher's quality bound would otherwise refine around without
  // end, at the cost of moving the surface by at most this fraction of a grid edge.
  double nodeClearance = 0.2;
};

// `surface` must be closed and consistently oriented outward (it may cross itself). Returns the
// boundary of the region it winds around, outward; empty when that region is thinner than the
// grid resolves.
TriMesh solidify(const TriMesh& surface, const SolidifyOptions& options);

}  // namespace galsculpt
