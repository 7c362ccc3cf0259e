#include "solver/mesh/surface_simplify.h"

#include <gtest/gtest.h>

#include "solver/mesh/shape_generators.h"
#include "solver/mesh/surface_checks.h"
#include "tests/surface_expectations.h"

namespace galsculpt {
namespace {

TEST(SurfaceSimplify, SphereKeepsShapeAndTopology) {
  const TriMesh fine = makeIcosphere(1.0, 4);  // 5120 faces
  const TriMesh coarse = simplifySurface(fine, 500);
  EXPECT_LE(coarse.numFaces(), 500);
  EXPECT_GE(coarse.numFaces(), 480) << "collapses remove two faces at a time";
  test::expectClosedEmbedded(coarse);
  EXPECT_NEAR(enclosedVolume(coarse) / enclosedVolume(fine), 1.0, 0.03);
  for (const Vec3& v : coarse.vertices)
    EXPECT_NEAR(v.norm(), 1.0, 0.03) << "vertices stay near the sphere";
}

TEST(SurfaceSimplify, NonConvexSlabStaysEmbedded) {
  const TriMesh fine = makeSteakSlab(0.003);
  const TriMesh coarse = simplifySurface(fine, fine.numFaces() / 10);
  EXPECT_LE(coarse.numFaces(), fine.numFaces() / 10);
  test::expectClosedEmbedded(coarse);
  EXPECT_NEAR(enclosedVolume(coarse) / enclosedVolume(fine), 1.0, 0.03);
}

TEST(SurfaceSimplify, FlatFacesCollapseWithoutError) {
  // The Charpy bar is already minimal: nothing can go without changing the shape much, and
  // whatever is collapsed must leave a valid closed surface with the same volume.
  const TriMesh bar = makeCharpyBar();
  const TriMesh out = simplifySurface(bar, 4);
  test::expectClosedEmbedded(out);
  EXPECT_GE(out.numFaces(), 4);
}

TEST(SurfaceSimplify, TargetAboveTheFaceCountIsANoOp) {
  const TriMesh m = makeIcosphere(1.0, 1);
  EXPECT_EQ(simplifySurface(m, 1000).faces, m.faces);
}

}  // namespace
}  // namespace galsculpt
