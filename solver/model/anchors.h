// Anchors: vertices held on a prescribed path (Dirichlet conditions). They are part of the
// state (SimState::anchors): tools add, move and remove them while a simulation runs.
#pragma once

#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct AnchorKey {
  double time = 0.0;
  Vec3 offset = Vec3::Zero();
};

struct AnchorConstraint {
  std::vector<int> vertices;    // anchored vertices
  std::vector<AnchorKey> path;  // empty: fixed; else offset(t), linear, held at the ends
  // Where each vertex sits at offset zero (same order as vertices); empty: its rest position.
  // Tools that grab a deformed body anchor it where it is.
  std::vector<Vec3> origin;
};

// The path's offset at `time` (linear between keys, held before the first and after the last).
Vec3 anchorOffset(const AnchorConstraint& anchor, double time);

}  // namespace galsculpt
