// Assertions on surfaces shared by the solver and engine tests.
#pragma once

#include <gtest/gtest.h>

#include "solver/surface_checks.h"

namespace galsculpt::test {

// One closed, consistently oriented, self-intersection-free piece enclosing positive volume.
inline void expectClosedEmbedded(const TriMesh& m) {
  const SurfaceTopology topo = analyzeSurface(m);
  EXPECT_TRUE(topo.closedManifold()) << topo.describeProblem();
  EXPECT_EQ(topo.pieces, 1);
  EXPECT_TRUE(findSelfIntersections(m, 1).empty());
  EXPECT_GT(enclosedVolume(m), 0.0) << "outward orientation";
}

}  // namespace galsculpt::test
