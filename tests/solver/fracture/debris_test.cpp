#include "solver/fracture/debris.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

SimModel barModel() {
  return buildSimModel(test::gridBar(2, 8, 2, 0.1),
                       {MaterialModel::StVK, lameFromYoungPoisson(1e5, 0.3), 1000.0, {}});
}

// Pieces over undamaged edges, each with the rest volume of its vertices' corner cells (a
// quarter of every tet around each vertex); the pieces' volumes add up to the body's.
TEST(Debris, CensusCountsPiecesAndTheirCornerCellVolumes) {
  const SimModel m = barModel();
  std::vector<std::uint8_t> damaged(m.numEdges(), 0);
  PieceCensus whole = censusPieces(m, damaged);
  ASSERT_EQ(whole.pieces, 1);
  double body = 0.0;
  for (const TetRest& r : m.rest) body += r.volume;
  EXPECT_NEAR(whole.bodyRestVolume, body, 1e-15);
  EXPECT_NEAR(whole.restVolume[0], body, 1e-15);
  EXPECT_EQ(whole.vertexCount[0], m.numVertices());
  EXPECT_TRUE(debrisVertices(whole, 0.5).empty()) << "one piece is never debris of itself";

  // Free vertex 0 (a corner) and cut the bar across the middle of its length.
  const double mid = 0.5 * 8 * 0.1;
  for (int e = 0; e < m.numEdges(); ++e) {
    const int a = m.edges[e][0], b = m.edges[e][1];
    const bool across = (m.mesh.vertices[a].y() < mid) != (m.mesh.vertices[b].y() < mid);
    if (a == 0 || b == 0 || across) damaged[e] = 1;
  }
  const PieceCensus c = censusPieces(m, damaged);
  ASSERT_EQ(c.pieces, 3);
  double corner = 0.0;
  for (int t = 0; t < m.numTets(); ++t)
    for (int v : m.mesh.tets[t])
      if (v == 0) corner += 0.25 * m.rest[t].volume;
  const int loose = c.pieceOfVertex[0];
  EXPECT_EQ(loose, 0) << "pieces are numbered in first-vertex order";
  EXPECT_EQ(c.vertexCount[loose], 1);
  EXPECT_NEAR(c.restVolume[loose], corner, 1e-15);
  double sum = 0.0;
  for (double v : c.restVolume) sum += v;
  EXPECT_NEAR(sum, body, 1e-14);
  for (int v = 0; v < m.numVertices(); ++v) ASSERT_LT(c.pieceOfVertex[v], c.pieces);

  // Debris is what lies under the fraction: the loose corner only, then everything.
  const std::vector<std::uint8_t> small = debrisVertices(c, 0.01);
  ASSERT_EQ(small.size(), static_cast<size_t>(m.numVertices()));
  EXPECT_EQ(std::count(small.begin(), small.end(), 1), 1);
  EXPECT_EQ(small[0], 1);
  EXPECT_EQ(debrisPieces(c, 0.01), (std::vector<std::uint8_t>{1, 0, 0}));
  EXPECT_EQ(debrisPieces(c, 0.6), (std::vector<std::uint8_t>{1, 1, 1}));
  EXPECT_TRUE(debrisVertices(c, 0.0).empty()) << "a fraction of 0 keeps everything";
}

// A sliver, a piece that holds no whole tet, is debris whatever its size: no element holds its
// shape (edge lengths alone let it turn inside out). Here two vertices joined by one intact edge,
// everything else around them damaged, with a fraction far below their corner cells' volume.
TEST(Debris, APieceHoldingNoWholeTetIsDebrisWhateverItsSize) {
  const SimModel m = barModel();
  std::vector<std::uint8_t> damaged(m.numEdges(), 0);
  int kept = -1;
  for (int e = 0; e < m.numEdges() && kept < 0; ++e)
    if (m.edges[e][0] == 0 || m.edges[e][1] == 0) kept = e;
  ASSERT_GE(kept, 0);
  const int a = m.edges[kept][0], b = m.edges[kept][1];
  for (int e = 0; e < m.numEdges(); ++e) {
    const bool touches =
        m.edges[e][0] == a || m.edges[e][1] == a || m.edges[e][0] == b || m.edges[e][1] == b;
    if (touches && e != kept) damaged[e] = 1;
  }
  const PieceCensus c = censusPieces(m, damaged);
  ASSERT_EQ(c.pieces, 2);
  const int sliver = c.pieceOfVertex[a];
  EXPECT_EQ(c.vertexCount[sliver], 2);
  EXPECT_EQ(c.wholeTets[sliver], 0);
  EXPECT_GT(c.wholeTets[1 - sliver], 0);
  // Each tet is whole exactly when its corners share a piece; the whole tets' rest volume is
  // what the pieces' material fills (the sliver's tets have a corner in the other piece).
  double wholeVolume = 0.0;
  int whole = 0;
  for (int t = 0; t < m.numTets(); ++t) {
    const Tet& tet = m.mesh.tets[t];
    const bool touchesSliver =
        c.pieceOfVertex[tet[0]] == sliver || c.pieceOfVertex[tet[1]] == sliver ||
        c.pieceOfVertex[tet[2]] == sliver || c.pieceOfVertex[tet[3]] == sliver;
    EXPECT_EQ(c.isWhole[t], touchesSliver ? 0 : 1) << "tet " << t;
    if (!touchesSliver) wholeVolume += m.rest[t].volume, ++whole;
  }
  EXPECT_EQ(whole, c.wholeTets[1 - sliver]);
  EXPECT_NEAR(c.wholeRestVolume, wholeVolume, 1e-12 * c.bodyRestVolume);
  EXPECT_LT(c.wholeRestVolume, c.bodyRestVolume);
  const double tiny = 1e-3 * c.restVolume[sliver] / c.bodyRestVolume;
  std::vector<std::uint8_t> expected(2, 0);
  expected[sliver] = 1;
  EXPECT_EQ(debrisPieces(c, tiny), expected);
  EXPECT_EQ(debrisPieces(c, 0.0), (std::vector<std::uint8_t>{0, 0})) << "0 keeps everything";
}

// Debris is sized by the material a piece holds, its whole tets, not by its corner cells: an
// end slab of the bar whose corner cells reach into the cracked layer beside it is debris at a
// fraction between the two.
TEST(Debris, APieceIsSizedByTheWholeTetsItHolds) {
  const SimModel m = barModel();
  std::vector<std::uint8_t> damaged(m.numEdges(), 0);
  const double cut = 0.15;  // between the first and second layers of cubes
  for (int e = 0; e < m.numEdges(); ++e) {
    const int a = m.edges[e][0], b = m.edges[e][1];
    damaged[e] = (m.mesh.vertices[a].y() < cut) != (m.mesh.vertices[b].y() < cut);
  }
  const PieceCensus c = censusPieces(m, damaged);
  ASSERT_EQ(c.pieces, 2);
  const int slab = c.pieceOfVertex[0];
  double layer = 0.0;
  for (int t = 0; t < m.numTets(); ++t) {
    bool inFirstLayer = true;
    for (const int v : m.mesh.tets[t]) inFirstLayer &= m.mesh.vertices[v].y() < cut;
    if (inFirstLayer) layer += m.rest[t].volume;
  }
  EXPECT_EQ(c.wholeTets[slab], 2 * 2 * 6);
  EXPECT_NEAR(c.wholeVolume[slab], layer, 1e-12 * c.bodyRestVolume);
  EXPECT_NEAR(c.wholeVolume[0] + c.wholeVolume[1], c.wholeRestVolume, 1e-12 * c.bodyRestVolume);
  ASSERT_GT(c.restVolume[slab], 1.2 * c.wholeVolume[slab]);
  const double between = 0.5 * (c.restVolume[slab] + c.wholeVolume[slab]) / c.bodyRestVolume;
  std::vector<std::uint8_t> expected(2, 0);
  expected[slab] = 1;
  EXPECT_EQ(debrisPieces(c, between), expected);
  EXPECT_EQ(debrisPieces(c, 0.9 * c.wholeVolume[slab] / c.bodyRestVolume),
            (std::vector<std::uint8_t>{0, 0}));
}

}  // namespace
}  // namespace galsculpt
