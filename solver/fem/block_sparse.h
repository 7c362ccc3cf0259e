// Symmetric-pattern sparse matrix of 3x3 blocks: one block row per vertex, one block per mesh
// edge (both directions) plus the diagonal. The pattern is built once from the tet mesh;
// damage changes values, never the pattern. Element matrices are added through a precomputed
// scatter map (tet, local a, local b) -> block index.
#pragma once

#include <Eigen/Sparse>
#include <array>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct BlockPattern {
  int rows = 0;
  std::vector<int> rowStart;  // (rows + 1)
  std::vector<int> columns;   // (nBlocks), sorted within each row
  std::vector<int> diagonal;  // (rows) index of block (i, i)

  int numBlocks() const { return static_cast<int>(columns.size()); }
  // Index of block (row, column), or -1 when it is not in the pattern.
  int find(int row, int column) const;
};

BlockPattern buildBlockPattern(int vertices, const std::vector<Edge>& edges);

// For each tet, the block index of (local a, local b), a and b in 0..3, row-major 4x4.
using TetScatter = std::array<int, 16>;
std::vector<TetScatter> buildTetScatter(const BlockPattern& pattern, const std::vector<Tet>& tets);

struct BlockSparseMatrix {
  const BlockPattern* pattern = nullptr;
  std::vector<Eigen::Matrix3d> blocks;  // (nBlocks)

  explicit BlockSparseMatrix(const BlockPattern& p)
      : pattern(&p), blocks(p.numBlocks(), Eigen::Matrix3d::Zero()) {}
  void setZero();
  // y = A x for vectors of length 3 * rows.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  Eigen::SparseMatrix<double> toEigen() const;
};

}  // namespace galsculpt
