#include "solver/mesh/mesh_stats.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(MeshStats, Cube) {
  const TetMeshStats s = computeStats(test::unitCubeTets(2.0, Vec3(-1, -1, -1)));
  EXPECT_EQ(s.vertices, 8);
  EXPECT_EQ(s.tets, 6);
  EXPECT_EQ(s.edges, 19);
  EXPECT_EQ(s.boundaryFaces, 12);
  EXPECT_NEAR(s.volume, 8.0, 1e-12);
  EXPECT_EQ(s.box.min, Vec3(-1, -1, -1));
  EXPECT_EQ(s.box.max, Vec3(1, 1, 1));
  EXPECT_TRUE(s.watertight);
  EXPECT_EQ(s.pieces, 1);
  int total = 0;
  for (int n : s.qualityHistogram) total += n;
  EXPECT_EQ(total, 6);
  EXPECT_GT(s.minQuality, 0.5);
  EXPECT_LE(s.meanQuality, 1.0);
}

TEST(MeshStats, TwoTetsSharingOnlyAnEdgeAreNotWatertight) {
  TetMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0),  Vec3(0, 1, 0),
                Vec3(0, 0, 1), Vec3(1, -1, 0), Vec3(1, 0, -1)};
  m.tets = {{0, 1, 2, 3}, {0, 1, 4, 5}};
  for (Tet& t : m.tets) {
    if (tetSixVolume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]) < 0)
      std::swap(t[2], t[3]);
  }
  const TetMeshStats s = computeStats(m);
  EXPECT_FALSE(s.watertight);
  EXPECT_NE(s.boundaryProblem.find("non-manifold"), std::string::npos) << s.boundaryProblem;
}

}  // namespace
}  // namespace galsculpt
