#include "solver/mesh/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "solver/mesh/surface_checks.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(TetMesh, CubeVolumeAndBoundary) {
  const TetMesh cube = test::unitCubeTets(2.0);
  for (int t = 0; t < cube.numTets(); ++t) EXPECT_GT(tetVolume(cube, t), 0.0);
  EXPECT_NEAR(totalVolume(cube), 8.0, 1e-12);
  const std::vector<Tri> faces = boundaryFaces(cube);
  EXPECT_EQ(faces.size(), 12u);
  const TriMesh surface = boundarySurface(cube);
  EXPECT_EQ(surface.numVertices(), 8);
  EXPECT_NEAR(enclosedVolume(surface), 8.0, 1e-12) << "boundary faces point outward";
  EXPECT_TRUE(analyzeSurface(surface).closedManifold());
}

// Each tet's neighbour across the face opposite corner k shares exactly that face, the relation
// is symmetric, and the faces without one are the boundary.
TEST(TetMesh, FaceNeighboursShareTheFaceBothWays) {
  const TetMesh bar = test::gridBar(3, 2, 2, 0.1);
  const std::vector<std::array<int, 4>> n = tetFaceNeighbours(bar);
  ASSERT_EQ(n.size(), bar.tets.size());
  int open = 0, links = 0;
  for (int t = 0; t < bar.numTets(); ++t) {
    for (int k = 0; k < 4; ++k) {
      if (n[t][k] < 0) {
        ++open;
        continue;
      }
      ++links;
      const Tet& other = bar.tets[n[t][k]];
      for (int a = 0; a < 4; ++a) {
        const bool shared = std::find(other.begin(), other.end(), bar.tets[t][a]) != other.end();
        EXPECT_EQ(shared, a != k) << "tet " << t << " face " << k;
      }
      const auto& back = n[n[t][k]];
      EXPECT_NE(std::find(back.begin(), back.end(), t), back.end());
    }
  }
  EXPECT_EQ(open, static_cast<int>(boundaryFaces(bar).size()));
  EXPECT_EQ(links, 4 * bar.numTets() - open);
  EXPECT_GT(links, 0);
  TetMesh one;
  one.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  one.tets = {{0, 1, 2, 3}};
  EXPECT_EQ(tetFaceNeighbours(one)[0], (std::array<int, 4>{-1, -1, -1, -1}));
}

TEST(TetMesh, OutwardFacesOfASingleTet) {
  TetMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.tets = {{0, 1, 2, 3}};
  const Vec3 centroid = Vec3(0.25, 0.25, 0.25);
  for (const Tri& f : tetFacesOutward(m.tets[0])) {
    const Vec3 n = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
    EXPECT_GT(n.dot(m.vertices[f[0]] - centroid), 0.0);
  }
}

TEST(TetMesh, UniqueEdgesOfCube) {
  // 12 cube edges + 6 face diagonals + 1 body diagonal.
  EXPECT_EQ(uniqueEdges(test::unitCubeTets()).size(), 19u);
}

TEST(TetMesh, MeanRatioIsOneForRegularAndSignedForInverted) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  EXPECT_NEAR(tetMeanRatio(a, b, d, c), 1.0, 1e-12);
  EXPECT_NEAR(tetMeanRatio(a, b, c, d), -1.0, 1e-12);
  // e sits just off the plane of a, b, c: (a, b, e, c) is nearly flat and scores near 0.
  const Vec3 e = (a + b + c) / 3.0 + 1e-3 * Vec3(1, 1, -1).normalized();
  EXPECT_GT(tetMeanRatio(a, b, e, c) * tetMeanRatio(a, b, c, e), -1e-3);
  EXPECT_LT(std::abs(tetMeanRatio(a, b, e, c)), 0.05);
}

TEST(TetMesh, PiecesCountSeparateParts) {
  TetMesh a = test::unitCubeTets();
  const TetMesh b = test::unitCubeTets(1.0, Vec3(5, 0, 0));
  for (const Vec3& v : b.vertices) a.vertices.push_back(v);
  for (Tet t : b.tets) {
    for (int& v : t) v += 8;
    a.tets.push_back(t);
  }
  a.vertices.push_back(Vec3(9, 9, 9));  // isolated vertex: no piece
  std::vector<int> piece;
  EXPECT_EQ(countPieces(a, &piece), 2);
  EXPECT_EQ(piece[0], 0);
  EXPECT_EQ(piece[8], 1);
  EXPECT_EQ(piece[16], -1);
}

}  // namespace
}  // namespace galsculpt
