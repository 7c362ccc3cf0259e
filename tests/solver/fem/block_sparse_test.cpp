#include "solver/fem/block_sparse.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(BlockSparse, PatternHoldsTheDiagonalAndEveryEdgeBothWays) {
  const TetMesh mesh = test::gridBar(2, 2, 2, 0.1);
  const std::vector<Edge> edges = uniqueEdges(mesh);
  const BlockPattern p = buildBlockPattern(mesh.numVertices(), edges);
  EXPECT_EQ(p.rows, mesh.numVertices());
  EXPECT_EQ(p.numBlocks(), mesh.numVertices() + 2 * static_cast<int>(edges.size()));
  for (int r = 0; r < p.rows; ++r) {
    EXPECT_EQ(p.columns[p.diagonal[r]], r);
    for (int k = p.rowStart[r] + 1; k < p.rowStart[r + 1]; ++k)
      EXPECT_LT(p.columns[k - 1], p.columns[k]) << "sorted within row " << r;
  }
  for (const Edge& e : edges) {
    EXPECT_GE(p.find(e[0], e[1]), 0);
    EXPECT_GE(p.find(e[1], e[0]), 0);
  }
  // Two vertices of the bar that share no edge: not in the pattern.
  const int far = mesh.numVertices() - 1;
  EXPECT_EQ(p.find(0, far), -1);
}

TEST(BlockSparse, ScatterMapsEveryTetBlockAndMultiplyMatchesEigen) {
  const TetMesh mesh = test::gridBar(3, 2, 2, 0.1);
  const BlockPattern p = buildBlockPattern(mesh.numVertices(), uniqueEdges(mesh));
  const std::vector<TetScatter> scatter = buildTetScatter(p, mesh.tets);
  ASSERT_EQ(scatter.size(), mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        EXPECT_EQ(scatter[t][4 * a + b], p.find(mesh.tets[t][a], mesh.tets[t][b]));
  BlockSparseMatrix m(p);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Eigen::Matrix3d& b : m.blocks) b = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
  Eigen::VectorXd x(3 * p.rows);
  for (int i = 0; i < x.size(); ++i) x[i] = u(rng);
  Eigen::VectorXd y;
  m.multiply(x, y);
  const Eigen::VectorXd expected = m.toEigen() * x;
  EXPECT_LT((y - expected).norm(), 1e-12 * expected.norm());
  m.setZero();
  for (const Eigen::Matrix3d& b : m.blocks) EXPECT_TRUE(b.isZero(0.0));
}

}  // namespace
}  // namespace galsculpt
