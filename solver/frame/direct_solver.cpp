#include "solver/frame/direct_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <vector>

namespace galsculpt {

struct DirectSolver::Impl {
  Eigen::SparseMatrix<double> matrix;
  std::vector<double*> entry;  // (9 blocks) where each block value lands in `matrix`
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> llt;
  bool analysed = false;
};

DirectSolver::DirectSolver(const BlockPattern& pattern) : impl_(std::make_unique<Impl>()) {
  const int n = pattern.rows;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * pattern.columns.size());
  for (int r = 0; r < n; ++r)
    for (int k = pattern.rowStart[r]; k < pattern.rowStart[r + 1]; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          triplets.emplace_back(3 * r + i, 3 * pattern.columns[k] + j, 1.0);
  Impl& m = *impl_;
  m.matrix.resize(3 * n, 3 * n);
  m.matrix.setFromTriplets(triplets.begin(), triplets.end());
  m.matrix.makeCompressed();
  m.entry.resize(9 * pattern.columns.size());
  for (int r = 0; r < n; ++r)
    for (int k = pattern.rowStart[r]; k < pattern.rowStart[r + 1]; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          m.entry[9 * k + i + 3 * j] = &m.matrix.coeffRef(3 * r + i, 3 * pattern.columns[k] + j);
}

DirectSolver::~DirectSolver() = default;

bool DirectSolver::solve(const double* blocks, const double* b, double* x) {
  Impl& m = *impl_;
  for (size_t i = 0; i < m.entry.size(); ++i) *m.entry[i] = blocks[i];
  if (!m.analysed) {
    m.llt.analyzePattern(m.matrix);
    m.analysed = true;
  }
  m.llt.factorize(m.matrix);
  if (m.llt.info() != Eigen::Success) return false;
  const Eigen::Map<const Eigen::VectorXd> rhs(b, m.matrix.rows());
  const Eigen::VectorXd solution = m.llt.solve(rhs);
  if (m.llt.info() != Eigen::Success) return false;
  Eigen::Map<Eigen::VectorXd>(x, m.matrix.rows()) = solution;
  return true;
}

}  // namespace galsculpt
