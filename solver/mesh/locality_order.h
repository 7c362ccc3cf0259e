// The order of a mesh's vertices and elements in memory: neighbours close together.
//
// TetGen numbers vertices and tets in the order its refinement made them, which is close to
// random in space: a tet's corners lie thousands of indices apart, and every pass over the
// elements (the stiffness, its gather into the matrix's blocks, the smoother's rows) reads and
// writes memory far beyond the caches. Ordering the vertices along a space-filling curve and the
// tets by their corners puts what one element, one matrix row or one smoother row touches on
// neighbouring cache lines.
//
// The order is a function of the positions alone (a stable sort on the curve's keys), so applying
// it to a mesh already in this order changes nothing: a mesh read back from the cache, or made
// again, ends in the same order.
#pragma once

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// Renumbers the vertices along a Morton (Z-order) curve over the bounding box and sorts the tets
// by their smallest corner, then their others (each tet's own corner order, its orientation,
// kept). Faces and markers follow their vertices. Stable: a mesh in this order is unchanged.
void orderForLocality(TetMesh& mesh);

}  // namespace galsculpt
