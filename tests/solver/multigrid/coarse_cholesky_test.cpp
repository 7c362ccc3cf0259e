#include "solver/multigrid/coarse_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

namespace galsculpt {
namespace {

// A symmetric positive definite matrix of 12x12 blocks where `coupled(a, b)` (symmetric, true on
// the diagonal), as block CSR with both triangles.
struct BlockMatrix {
  int handles = 0;
  std::vector<int> rowStart, columns;
  std::vector<double> blocks;
  Eigen::MatrixXd dense;
};

template <class Coupled>
BlockMatrix coupledBy(int handles, Coupled coupled, double shift) {
  BlockMatrix m;
  m.handles = handles;
  const int n = 12 * handles;
  Eigen::MatrixXd random = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      random(i, j) = std::sin(1.0 + 3.0 * i + 7.0 * j * j);  // deterministic, fills every block
  for (int a = 0; a < handles; ++a)
    for (int b = 0; b < handles; ++b)
      if (!coupled(a, b)) random.block<12, 12>(12 * a, 12 * b).setZero();
  // Diagonally dominant with the sparsity of `coupled`: positive definite for shift > 0.
  m.dense = 0.5 * (random + random.transpose());
  for (int i = 0; i < n; ++i) m.dense(i, i) = m.dense.row(i).cwiseAbs().sum() + shift;
  m.rowStart.push_back(0);
  for (int a = 0; a < handles; ++a) {
    for (int b = 0; b < handles; ++b) {
      if (!coupled(a, b)) continue;
      m.columns.push_back(b);
      const Eigen::Matrix<double, 12, 12> blk = m.dense.block<12, 12>(12 * a, 12 * b);
      m.blocks.insert(m.blocks.end(), blk.data(), blk.data() + 144);
    }
    m.rowStart.push_back(static_cast<int>(m.columns.size()));
  }
  return m;
}

// A chain of handles, each coupled to the next; `extra` adds the pair (0, last).
BlockMatrix chain(int handles, bool extra, double shift = 1.0) {
  return coupledBy(
      handles,
      [&](int a, int b) {
        return std::abs(a - b) <= 1 ||
               (extra && ((a == 0 && b == handles - 1) || (b == 0 && a == handles - 1)));
      },
      shift);
}

// Handles on an nx x ny x nz grid, each coupled to its 26 neighbours: a factor with fill, whose
// elimination tree passes rows up from children (the coarse levels of a body are like this).
BlockMatrix grid(int nx, int ny, int nz) {
  const auto cell = [=](int h, int axis) {
    return axis == 0 ? h % nx : (axis == 1 ? h / nx % ny : h / (nx * ny));
  };
  return coupledBy(
      nx * ny * nz,
      [&](int a, int b) {
        for (int axis = 0; axis < 3; ++axis)
          if (std::abs(cell(a, axis) - cell(b, axis)) > 1) return false;
        return true;
      },
      1.0);
}

Eigen::VectorXd rhs(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.3 * i) + 0.1 * i;
  return b;
}

double solveError(CoarseCholesky& c, const BlockMatrix& m) {
  const Eigen::VectorXd b = rhs(12 * m.handles);
  Eigen::VectorXd x = b;
  c.solve(x.data());
  const Eigen::VectorXd exact = m.dense.llt().solve(b);
  return (x - exact).norm() / exact.norm();
}

TEST(CoarseCholesky, SolvesLikeTheDenseFactorizationAndFollowsPatternChanges) {
  CoarseCholesky c;
  const BlockMatrix a = chain(9, false);
  ASSERT_TRUE(c.factor(a.handles, a.rowStart.data(), a.columns.data(), a.blocks.data()));
  EXPECT_LT(solveError(c, a), 1e-12);
  // New values on the same pattern, then a new pattern (the ordering analysed again).
  const BlockMatrix shifted = chain(9, false, 5.0);
  ASSERT_TRUE(c.factor(shifted.handles, shifted.rowStart.data(), shifted.columns.data(),
                       shifted.blocks.data()));
  EXPECT_LT(solveError(c, shifted), 1e-12);
  const BlockMatrix ring = chain(9, true);
  ASSERT_TRUE(
      c.factor(ring.handles, ring.rowStart.data(), ring.columns.data(), ring.blocks.data()));
  EXPECT_LT(solveError(c, ring), 1e-12);
  const BlockMatrix larger = chain(14, true);
  ASSERT_TRUE(c.factor(larger.handles, larger.rowStart.data(), larger.columns.data(),
                       larger.blocks.data()));
  EXPECT_LT(solveError(c, larger), 1e-12);
}

TEST(CoarseCholesky, SolvesAGridOfHandlesWithFillAndWithHandlesInAnyOrder) {
  const BlockMatrix g = grid(4, 3, 3);
  CoarseCholesky c;
  ASSERT_TRUE(c.factor(g.handles, g.rowStart.data(), g.columns.data(), g.blocks.data()));
  EXPECT_LT(solveError(c, g), 1e-12);
  // The same matrix again (the kept analysis): the same solution to the last bit.
  const Eigen::VectorXd b = rhs(12 * g.handles);
  Eigen::VectorXd first = b, second = b;
  c.solve(first.data());
  ASSERT_TRUE(c.factor(g.handles, g.rowStart.data(), g.columns.data(), g.blocks.data()));
  c.solve(second.data());
  EXPECT_EQ(first, second);
}

TEST(CoarseCholesky, RefusesAMatrixWithANaN) {
  CoarseCholesky c;
  BlockMatrix m = grid(3, 2, 2);
  // In handle 5's diagonal block (the factor reads one triangle of a symmetric matrix).
  int diagonal = m.rowStart[5];
  while (m.columns[diagonal] != 5) ++diagonal;
  m.blocks[144 * diagonal + 13] = std::nan("");
  EXPECT_FALSE(c.factor(m.handles, m.rowStart.data(), m.columns.data(), m.blocks.data()));
  // A good matrix on the same pattern factors again afterwards.
  const BlockMatrix good = grid(3, 2, 2);
  ASSERT_TRUE(
      c.factor(good.handles, good.rowStart.data(), good.columns.data(), good.blocks.data()));
  EXPECT_LT(solveError(c, good), 1e-12);
}

TEST(CoarseCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  CoarseCholesky c;
  BlockMatrix m = chain(5, false);
  // Negate the last handle's diagonal block: an indefinite matrix.
  const int last = m.rowStart[m.handles] - 1;  // the last row's last block: (4, 4)
  ASSERT_EQ(m.columns[last], m.handles - 1);
  for (int i = 0; i < 144; ++i) m.blocks[144 * last + i] = -m.blocks[144 * last + i];
  EXPECT_FALSE(c.factor(m.handles, m.rowStart.data(), m.columns.data(), m.blocks.data()));
}

}  // namespace
}  // namespace galsculpt
