#include "solver/fem/block_sparse.h"

#include <algorithm>

#include "solver/frame/parallel.h"

namespace galsculpt {

int BlockPattern::find(int row, int column) const {
  const auto begin = columns.begin() + rowStart[row];
  const auto end = columns.begin() + rowStart[row + 1];
  const auto it = std::lower_bound(begin, end, column);
  return (it != end && *it == column) ? static_cast<int>(it - columns.begin()) : -1;
}

BlockPattern buildBlockPattern(int vertices, const std::vector<Edge>& edges) {
  std::vector<std::vector<int>> adjacency(vertices);
  for (int v = 0; v < vertices; ++v) adjacency[v].push_back(v);
  for (const Edge& e : edges) {
    adjacency[e[0]].push_back(e[1]);
    adjacency[e[1]].push_back(e[0]);
  }
  BlockPattern p;
  p.rows = vertices;
  p.rowStart.assign(vertices + 1, 0);
  p.diagonal.resize(vertices);
  for (int v = 0; v < vertices; ++v) {
    std::sort(adjacency[v].begin(), adjacency[v].end());
    adjacency[v].erase(std::unique(adjacency[v].begin(), adjacency[v].end()), adjacency[v].end());
    p.rowStart[v + 1] = p.rowStart[v] + static_cast<int>(adjacency[v].size());
  }
  p.columns.reserve(p.rowStart[vertices]);
  for (int v = 0; v < vertices; ++v) {
    for (int c : adjacency[v]) {
      if (c == v) p.diagonal[v] = static_cast<int>(p.columns.size());
      p.columns.push_back(c);
    }
  }
  return p;
}

std::vector<TetScatter> buildTetScatter(const BlockPattern& pattern, const std::vector<Tet>& tets) {
  std::vector<TetScatter> scatter(tets.size());
  for (size_t t = 0; t < tets.size(); ++t) {
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) scatter[t][4 * a + b] = pattern.find(tets[t][a], tets[t][b]);
    }
  }
  return scatter;
}

void BlockSparseMatrix::setZero() {
  for (Eigen::Matrix3d& b : blocks) b.setZero();
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const BlockPattern& p = *pattern;
  y.resize(3 * p.rows);
  parallelFor(
      p.rows,
      [&](int r) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int k = p.rowStart[r]; k < p.rowStart[r + 1]; ++k)
          sum.noalias() += blocks[k] * x.segment<3>(3 * p.columns[k]);
        y.segment<3>(3 * r) = sum;
      },
      150);
}

Eigen::SparseMatrix<double> BlockSparseMatrix::toEigen() const {
  const BlockPattern& p = *pattern;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(blocks.size() * 9);
  for (int r = 0; r < p.rows; ++r) {
    for (int k = p.rowStart[r]; k < p.rowStart[r + 1]; ++k) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
          triplets.emplace_back(3 * r + i, 3 * p.columns[k] + j, blocks[k](i, j));
      }
    }
  }
  Eigen::SparseMatrix<double> m(3 * p.rows, 3 * p.rows);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

}  // namespace galsculpt
