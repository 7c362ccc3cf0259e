#include "solver/mesh/locality_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

// A grid bar with its vertices and tets numbered at random (as TetGen leaves them), each vertex
// marked with its grid index and the boundary faces kept.
TetMesh shuffledBar() {
  TetMesh mesh = test::gridBar(16, 12, 12, 0.1);
  const int n = mesh.numVertices();
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(7);
  std::shuffle(perm.begin(), perm.end(), rng);
  TetMesh out;
  out.vertices.resize(n);
  out.vertexMarkers.resize(n);
  for (int v = 0; v < n; ++v) {
    out.vertices[perm[v]] = mesh.vertices[v];
    out.vertexMarkers[perm[v]] = v;
  }
  for (Tet t : mesh.tets) {
    for (int& v : t) v = perm[v];
    out.tets.push_back(t);
  }
  std::shuffle(out.tets.begin(), out.tets.end(), rng);
  out.faces = boundaryFaces(out);
  return out;
}

// A tet as its corners' positions, in its own corner order (its orientation).
std::vector<double> cornerPositions(const TetMesh& mesh, const Tet& t) {
  std::vector<double> p;
  for (int v : t)
    for (int k = 0; k < 3; ++k) p.push_back(mesh.vertices[v][k]);
  return p;
}

double meanCornerSpread(const TetMesh& mesh) {
  double sum = 0.0;
  for (const Tet& t : mesh.tets)
    sum += *std::max_element(t.begin(), t.end()) - *std::min_element(t.begin(), t.end());
  return sum / mesh.numTets();
}

TEST(LocalityOrder, KeepsTheMeshAndPutsEachTetsCornersClose) {
  const TetMesh before = shuffledBar();
  TetMesh after = before;
  orderForLocality(after);
  ASSERT_EQ(after.numVertices(), before.numVertices());
  ASSERT_EQ(after.numTets(), before.numTets());
  // The same tets, corner by corner in the same order (so the same orientation and volume).
  std::vector<std::vector<double>> a, b;
  for (const Tet& t : before.tets) a.push_back(cornerPositions(before, t));
  for (const Tet& t : after.tets) b.push_back(cornerPositions(after, t));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  for (int t = 0; t < after.numTets(); ++t) EXPECT_GT(tetVolume(after, t), 0.0) << t;
  // Markers and faces follow their vertices.
  std::map<int, Vec3> byMarker;
  for (int v = 0; v < before.numVertices(); ++v)
    byMarker[before.vertexMarkers[v]] = before.vertices[v];
  for (int v = 0; v < after.numVertices(); ++v)
    EXPECT_EQ(after.vertices[v], byMarker[after.vertexMarkers[v]]) << v;
  ASSERT_EQ(after.faces.size(), before.faces.size());
  for (size_t f = 0; f < after.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(after.vertices[after.faces[f][k]], before.vertices[before.faces[f][k]]) << f;
  // Tets by their smallest corner; corners close together.
  for (int t = 1; t < after.numTets(); ++t) {
    const Tet &p = after.tets[t - 1], &q = after.tets[t];
    EXPECT_LE(*std::min_element(p.begin(), p.end()), *std::min_element(q.begin(), q.end())) << t;
  }
  EXPECT_LT(meanCornerSpread(after), 0.25 * meanCornerSpread(before))
      << meanCornerSpread(after) << " against " << meanCornerSpread(before);
}

// The order depends on the positions alone: a mesh in it is left as it is, and the same mesh
// numbered another way ends in the same order.
TEST(LocalityOrder, IsAFixedPointAndIndependentOfTheNumbering) {
  TetMesh once = shuffledBar();
  orderForLocality(once);
  TetMesh twice = once;
  orderForLocality(twice);
  EXPECT_EQ(twice.vertices, once.vertices);
  EXPECT_EQ(twice.tets, once.tets);
  EXPECT_EQ(twice.vertexMarkers, once.vertexMarkers);
  TetMesh grid = test::gridBar(16, 12, 12, 0.1);
  orderForLocality(grid);
  EXPECT_EQ(grid.vertices, once.vertices);
  EXPECT_EQ(grid.tets, once.tets) << "the same tets in the same order";
}

TEST(LocalityOrder, LeavesAnEmptyMeshEmpty) {
  TetMesh empty;
  orderForLocality(empty);
  EXPECT_EQ(empty.numVertices(), 0);
  EXPECT_EQ(empty.numTets(), 0);
}

}  // namespace
}  // namespace galsculpt
