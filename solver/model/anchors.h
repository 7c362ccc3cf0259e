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
  // Empty: each vertex held exactly on its path (a Dirichlet condition). Otherwise a weight
  // w in (0, 1] per vertex (same order): the vertex is pulled toward its target by a spring of
  // stiffness w kAnchorSpring mu V^(1/3) (mu the shear modulus, V the vertex's lumped volume),
  // stiff where w is 1 and nothing where w falls to 0: the shaping brushes hold this way, so a
  // vertex at their rim is not switched between held and free (held_vertices.h).
  std::vector<double> springWeights;
};

// A soft anchor's stiffness at weight 1, in units of mu V^(1/3): a vertex at the centre of a brush
// lags its target by about 1 / kAnchorSpring of the elastic forces on it.
inline constexpr double kAnchorSpring = 100.0;

// The path's offset at `time` (linear between keys, held before the first and after the last).
Vec3 anchorOffset(const AnchorConstraint& anchor, double time);

}  // namespace galsculpt
