#include "engine/surface/solidify.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/mesh/surface_checks.h"

namespace galsculpt {
namespace {

// An axis-aligned box's 12 triangles, outward (or inward with `inverted`), appended to `mesh`.
void addBox(TriMesh& mesh, const Vec3& lo, const Vec3& hi, bool inverted = false) {
  const int base = mesh.numVertices();
  for (int bits = 0; bits < 8; ++bits)
    mesh.vertices.emplace_back(bits & 1 ? hi.x() : lo.x(), bits & 2 ? hi.y() : lo.y(),
                               bits & 4 ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    Tri a{base + q[0], base + q[1], base + q[2]}, b{base + q[0], base + q[2], base + q[3]};
    if (inverted) {
      std::swap(a[1], a[2]);
      std::swap(b[1], b[2]);
    }
    mesh.faces.push_back(a);
    mesh.faces.push_back(b);
  }
}

void expectClosedAndClean(const TriMesh& mesh, int shells) {
  const SurfaceTopology topo = analyzeSurface(mesh);
  EXPECT_TRUE(topo.closedManifold()) << topo.describeProblem();
  EXPECT_EQ(countSurfacePieces(mesh), shells);
  EXPECT_TRUE(findSelfIntersections(mesh, 10).empty());
}

TEST(Solidify, ABoxKeepsItsVolume) {
  TriMesh box;
  addBox(box, Vec3(0, 0, 0), Vec3(1, 0.5, 0.25));
  ASSERT_NEAR(enclosedVolume(box), 0.125, 1e-12);
  const TriMesh solid = solidify(box, {.cell = 0.02});
  expectClosedAndClean(solid, 1);
  // Faces are found exactly; the edges and corners are cut by at most a cell's diagonal.
  EXPECT_NEAR(enclosedVolume(solid), 0.125, 0.02 * 0.125);
  EXPECT_GT(enclosedVolume(solid), 0.0);
}

TEST(Solidify, TwoBoxesThatCrossBecomeTheirUnion) {
  // One surface with two closed sheets passing through each other (what a folded piece is).
  TriMesh crossing;
  addBox(crossing, Vec3(0, 0, 0), Vec3(1, 1, 1));
  addBox(crossing, Vec3(0.5, 0.1, 0.2), Vec3(1.5, 1.1, 0.8));
  ASSERT_FALSE(findSelfIntersections(crossing, 1).empty());
  const TriMesh solid = solidify(crossing, {.cell = 0.025});
  expectClosedAndClean(solid, 1);
  const double overlap = 0.5 * 0.9 * 0.6;
  EXPECT_NEAR(enclosedVolume(solid), 1.0 + 0.6 - overlap, 0.02);
}

TEST(Solidify, AnInsideOutSheetCutsAwayWhatItOverlaps) {
  // A box turned inside out within a larger one winds the space it overlaps back to zero: the
  // region is the larger box with a cavity, two shells, the cavity's facing inwards.
  TriMesh mesh;
  addBox(mesh, Vec3(0, 0, 0), Vec3(1, 1, 1));
  addBox(mesh, Vec3(0.3, 0.3, 0.3), Vec3(0.7, 0.7, 0.7), /*inverted=*/true);
  const TriMesh solid = solidify(mesh, {.cell = 0.025});
  expectClosedAndClean(solid, 2);
  EXPECT_NEAR(enclosedVolume(solid), 1.0 - 0.064, 0.02);
}

TEST(Solidify, ASheetThinnerThanTheGridLeavesNothing) {
  TriMesh sliver;
  addBox(sliver, Vec3(0, 0, 0), Vec3(1, 1, 0.001));
  EXPECT_TRUE(solidify(sliver, {.cell = 0.1}).faces.empty());
}

TEST(Solidify, TheGridGrowsToItsNodeBound) {
  TriMesh box;
  addBox(box, Vec3(0, 0, 0), Vec3(1, 1, 1));
  const TriMesh coarse = solidify(box, {.cell = 1e-4, .maxNodes = 20000});
  expectClosedAndClean(coarse, 1);
  EXPECT_NEAR(enclosedVolume(coarse), 1.0, 0.1);
  EXPECT_THROW(solidify(box, {.cell = 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace galsculpt
