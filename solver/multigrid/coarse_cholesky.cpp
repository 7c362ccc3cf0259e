#include "solver/multigrid/coarse_cholesky.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <vector>

namespace galsculpt {

struct CoarseCholesky::Impl {
  std::vector<int> rowStart, columns;          // the analysed pattern
  Eigen::SparseMatrix<double> lower;           // the lower triangle, which the factorization reads
  std::vector<std::pair<double*, int>> entry;  // where each lower entry's value comes from
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt;

  void analyse(int handles, const int* start, const int* cols) {
    rowStart.assign(start, start + handles + 1);
    columns.assign(cols, cols + rowStart.back());
    // One walk over the lower entries: where each sits and which block value it takes.
    std::vector<Eigen::Triplet<double>> triplets;
    std::vector<int> from;
    for (int r = 0; r < handles; ++r)
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
        for (int j = 0; j < 12; ++j)
          for (int i = 0; i < 12; ++i)
            if (12 * r + i >= 12 * columns[k] + j) {
              triplets.emplace_back(12 * r + i, 12 * columns[k] + j, 0.0);
              from.push_back(144 * k + i + 12 * j);
            }
    lower.resize(12 * handles, 12 * handles);
    lower.setFromTriplets(triplets.begin(), triplets.end());
    lower.makeCompressed();
    entry.clear();
    for (size_t n = 0; n < triplets.size(); ++n)
      entry.emplace_back(&lower.coeffRef(triplets[n].row(), triplets[n].col()), from[n]);
    llt.analyzePattern(lower);
  }
};

CoarseCholesky::CoarseCholesky() : impl_(std::make_unique<Impl>()) {}
CoarseCholesky::~CoarseCholesky() = default;

bool CoarseCholesky::factor(int handles, const int* rowStart, const int* columns,
                            const double* blocks) {
  Impl& m = *impl_;
  const bool samePattern = static_cast<int>(m.rowStart.size()) == handles + 1 &&
                           std::equal(m.rowStart.begin(), m.rowStart.end(), rowStart) &&
                           std::equal(m.columns.begin(), m.columns.end(), columns);
  if (!samePattern) m.analyse(handles, rowStart, columns);
  for (const auto& [value, from] : m.entry) *value = blocks[from];
  m.llt.factorize(m.lower);
  return m.llt.info() == Eigen::Success;
}

void CoarseCholesky::solve(double* x) const {
  const Impl& m = *impl_;
  Eigen::Map<Eigen::VectorXd> v(x, m.lower.rows());
  v = m.llt.solve(v).eval();
}

}  // namespace galsculpt
