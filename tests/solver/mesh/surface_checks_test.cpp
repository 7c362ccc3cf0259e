#include "solver/mesh/surface_checks.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "solver/mesh/shape_generators.h"

namespace galsculpt {
namespace {

TriMesh merged(const TriMesh& a, const TriMesh& b, const Vec3& shift) {
  TriMesh m = a;
  const int offset = m.numVertices();
  for (const Vec3& v : b.vertices) m.vertices.push_back(v + shift);
  for (Tri f : b.faces) {
    for (int& i : f) i += offset;
    m.faces.push_back(f);
  }
  return m;
}

TEST(SurfaceChecks, ClosedSphere) {
  const TriMesh m = makeIcosphere(1.0, 2);
  const SurfaceTopology t = analyzeSurface(m);
  EXPECT_TRUE(t.closedManifold());
  EXPECT_EQ(t.describeProblem(), "");
  EXPECT_EQ(t.pieces, 1);
  EXPECT_NEAR(surfaceArea(m), 4 * M_PI, 0.3);
}

TEST(SurfaceChecks, OpenSurfaceNamesABoundaryEdge) {
  TriMesh m = makeIcosphere(1.0, 1);
  m.faces.pop_back();
  const SurfaceTopology t = analyzeSurface(m);
  EXPECT_EQ(t.boundaryEdges, 3);
  EXPECT_NE(t.describeProblem().find("open: 3 boundary edge(s)"), std::string::npos)
      << t.describeProblem();
}

TEST(SurfaceChecks, FlippedFaceIsInconsistent) {
  TriMesh m = makeIcosphere(1.0, 1);
  std::swap(m.faces[5][1], m.faces[5][2]);
  const SurfaceTopology t = analyzeSurface(m);
  EXPECT_EQ(t.inconsistentEdges, 3);
  EXPECT_NE(t.describeProblem().find("inconsistently oriented"), std::string::npos);
}

TEST(SurfaceChecks, ThreeFacesOnAnEdgeAreNonManifold) {
  TriMesh m = makeIcosphere(1.0, 1);
  const Tri f = m.faces[0];
  m.vertices.push_back(Vec3(3, 3, 3));
  m.faces.push_back({f[0], f[1], m.numVertices() - 1});
  const SurfaceTopology t = analyzeSurface(m);
  EXPECT_GE(t.nonManifoldEdges, 1);
  EXPECT_NE(t.describeProblem().find("non-manifold"), std::string::npos);
}

TEST(SurfaceChecks, TwoSpheresTouchingAtAVertexAreNonManifold) {
  const TriMesh a = makeIcosphere(1.0, 1);
  TriMesh m = merged(a, a, Vec3(0, 0, 0));
  // Weld one vertex of the second copy onto the first: a pinch point.
  const int n = a.numVertices();
  for (Tri& f : m.faces) {
    for (int& i : f) {
      if (i == n) i = 0;
    }
  }
  const SurfaceTopology t = analyzeSurface(m);
  EXPECT_EQ(t.nonManifoldVertices, 1);
}

TEST(SurfaceChecks, OverlappingSpheresIntersect) {
  const TriMesh a = makeIcosphere(1.0, 2);
  const TriMesh both = merged(a, a, Vec3(1.0, 0.1, 0.05));
  EXPECT_TRUE(analyzeSurface(both).closedManifold()) << "topologically fine, geometrically not";
  EXPECT_FALSE(findSelfIntersections(both).empty());
  EXPECT_TRUE(findSelfIntersections(merged(a, a, Vec3(3.0, 0, 0))).empty());
  EXPECT_EQ(countSurfacePieces(both), 2);
}

TEST(SurfaceChecks, SmallFacesCrossingByAHundredthOfTheirSizeCrossWhateverTheMeshsSize) {
  // Two faces a ten-thousandth of the mesh's size, one piercing the other by a hundredth of
  // their own size: a dead zone relative to the mesh called them touching (TetGen did not).
  TriMesh mesh = makeIcosphere(1.0, 2);
  const Vec3 p(2.0, 0.0, 0.0);
  const double h = 1e-4;
  const int base = mesh.numVertices();
  for (const Vec3& v : {p, Vec3(p + Vec3(h, 0, 0)), Vec3(p + Vec3(0, h, 0))})
    mesh.vertices.push_back(v);
  const Vec3 q = p + Vec3(0.2 * h, 0.2 * h, 0.0);
  for (const Vec3& v : {Vec3(q - Vec3(0, 0, 0.01 * h)), Vec3(q + Vec3(0, 0, 0.01 * h)),
                        Vec3(q + Vec3(0.5 * h, 0, 0))})
    mesh.vertices.push_back(v);
  mesh.faces.push_back({base, base + 1, base + 2});
  mesh.faces.push_back({base + 3, base + 4, base + 5});
  const auto pairs = findSelfIntersections(mesh, 10);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(mesh.numFaces() - 2, mesh.numFaces() - 1));
  // Lifted clear of the first by a hundredth of their size, they no longer cross.
  for (int k = 3; k < 6; ++k) mesh.vertices[base + k].z() += 0.02 * h;
  EXPECT_TRUE(findSelfIntersections(mesh, 10).empty());
}

TEST(SurfaceChecks, CrossingPairsAreListedOnceInOrderAndAMaskTestsOnlyThePairsItTouches) {
  const TriMesh a = makeIcosphere(1.0, 2);
  const TriMesh both = merged(a, a, Vec3(1.0, 0.1, 0.05));
  const std::vector<std::pair<int, int>> all = findSelfIntersections(both, 100000);
  ASSERT_GT(all.size(), 4u);
  EXPECT_TRUE(std::is_sorted(all.begin(), all.end()));
  EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end()) << "each pair once";
  // Every crossing pair is one face of each sphere, found whatever the grid.
  for (const auto& [f, g] : all) {
    EXPECT_LT(f, a.numFaces());
    EXPECT_GE(g, a.numFaces());
  }
  // Marking the faces of one crossing pair's first face finds exactly the pairs it is in.
  std::vector<char> mask(both.faces.size(), 0);
  mask[all[0].first] = 1;
  std::vector<std::pair<int, int>> expected;
  for (const auto& pair : all)
    if (pair.first == all[0].first || pair.second == all[0].first) expected.push_back(pair);
  EXPECT_EQ(findSelfIntersections(both, 100000, &mask), expected);
  std::fill(mask.begin(), mask.end(), 0);
  EXPECT_TRUE(findSelfIntersections(both, 100000, &mask).empty());
}

TEST(SurfaceChecks, VolumeSignFollowsOrientation) {
  TriMesh m = makeIcosphere(2.0, 3);
  const double v = enclosedVolume(m);
  EXPECT_NEAR(v, 4.0 / 3.0 * M_PI * 8.0, 0.02 * v);
  for (Tri& f : m.faces) std::swap(f[1], f[2]);
  EXPECT_NEAR(enclosedVolume(m), -v, 1e-9);
}

// Each shell's volume apart: a ball and, far from it, a small one turned inside out.
TEST(SurfaceChecks, EnclosedVolumesArePerGroup) {
  const TriMesh big = makeIcosphere(2.0, 3);
  TriMesh small = makeIcosphere(0.5, 2);
  for (Tri& f : small.faces) std::swap(f[1], f[2]);
  const TriMesh both = merged(big, small, Vec3(10.0, 0, 0));
  std::vector<int> shellOfFace;
  ASSERT_EQ(countSurfacePieces(both, &shellOfFace), 2);
  const std::vector<double> v = enclosedVolumes(both, shellOfFace, 2);
  const int bigShell = shellOfFace.front();
  EXPECT_NEAR(v[bigShell], enclosedVolume(big), 1e-9);
  EXPECT_NEAR(v[1 - bigShell], enclosedVolume(small), 1e-9);
  EXPECT_LT(v[1 - bigShell], 0.0);
  EXPECT_NEAR(v[0] + v[1], enclosedVolume(both), 1e-9);
}

}  // namespace
}  // namespace galsculpt
