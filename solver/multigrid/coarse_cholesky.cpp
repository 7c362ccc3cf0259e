#include "solver/multigrid/coarse_cholesky.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <vector>

namespace galsculpt {

namespace {

using Block = Eigen::Matrix<double, 12, 12>;
using BlockMap = Eigen::Map<Block>;
using ConstBlockMap = Eigen::Map<const Block>;
using Segment = Eigen::Map<Eigen::Matrix<double, 12, 1>>;

constexpr int kBlock = 144;

}  // namespace

// L = P A P^T's factor by handles: a 12x12 diagonal block per handle and the off-diagonal blocks
// of each block column (rows below it, ascending), in the order AMD chose for the handle graph.
struct CoarseCholesky::Impl {
  int handles = 0;
  std::vector<int> rowStart, columns;  // the analysed pattern (input order, both triangles)
  std::vector<int> order;              // order[new] = input handle
  std::vector<int> colStart, rows;     // L's block columns: rows (new numbering) below the diagonal
  std::vector<int> rowListStart, rowListColumn, rowListSlot;  // L's block rows left of the diagonal
  std::vector<int> target;              // per input block: slot in L (>= 0), -1 - diagonal, or skip
  std::vector<double> diagonal, lower;  // L's blocks, column-major
  std::vector<int> slotOfRow;           // workspace: the current column's slot of each row, or -1
  mutable std::vector<double> y;        // workspace of solve: the right-hand side in L's order
  static constexpr int kSkip = -(1 << 30);

  void analyse(int n, const int* start, const int* cols) {
    handles = n;
    rowStart.assign(start, start + n + 1);
    columns.assign(cols, cols + rowStart.back());
    // AMD on the handle graph (the blocks are dense, so the graph's fill is the matrix's).
    std::vector<Eigen::Triplet<double>> entries;
    for (int r = 0; r < n; ++r)
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) entries.emplace_back(r, columns[k], 1.0);
    Eigen::SparseMatrix<double> graph(n, n);
    graph.setFromTriplets(entries.begin(), entries.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
    Eigen::AMDOrdering<int>()(graph, amd);
    order.assign(amd.indices().data(), amd.indices().data() + n);
    std::vector<int> position(n);
    for (int j = 0; j < n; ++j) position[order[j]] = j;
    // Symbolic factorization: column j's rows are its own below-diagonal neighbours and those its
    // children in the elimination tree pass up (their rows below j).
    std::vector<std::vector<int>> pattern(n), children(n);
    for (int j = 0; j < n; ++j) {
      std::vector<int> below;
      const int r = order[j];
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
        if (position[columns[k]] > j) below.push_back(position[columns[k]]);
      for (int child : children[j])
        for (int i : pattern[child])
          if (i > j) below.push_back(i);
      std::sort(below.begin(), below.end());
      below.erase(std::unique(below.begin(), below.end()), below.end());
      pattern[j] = std::move(below);
      if (!pattern[j].empty()) children[pattern[j].front()].push_back(j);
    }
    colStart.assign(n + 1, 0);
    rows.clear();
    std::vector<std::vector<std::pair<int, int>>> rowLists(n);  // (column, slot) left of diagonal
    for (int j = 0; j < n; ++j) {
      for (int i : pattern[j]) {
        rowLists[i].emplace_back(j, static_cast<int>(rows.size()));
        rows.push_back(i);
      }
      colStart[j + 1] = static_cast<int>(rows.size());
    }
    rowListStart.assign(n + 1, 0);
    rowListColumn.clear();
    rowListSlot.clear();
    for (int i = 0; i < n; ++i) {
      for (const auto& [column, slot] : rowLists[i]) {
        rowListColumn.push_back(column);
        rowListSlot.push_back(slot);
      }
      rowListStart[i + 1] = static_cast<int>(rowListColumn.size());
    }
    // Where each input block lands: the lower triangle of P A P^T only (A is symmetric).
    slotOfRow.assign(n, -1);
    target.assign(columns.size(), kSkip);
    for (int r = 0; r < n; ++r)
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
        const int i = position[r], j = position[columns[k]];
        if (i == j) {
          target[k] = -1 - j;
        } else if (i > j) {
          const auto first = rows.begin() + colStart[j], last = rows.begin() + colStart[j + 1];
          target[k] = static_cast<int>(std::lower_bound(first, last, i) - rows.begin());
        }
      }
    diagonal.assign(static_cast<size_t>(kBlock) * n, 0.0);
    lower.assign(static_cast<size_t>(kBlock) * rows.size(), 0.0);
  }

  // Left-looking: column j gathers A's blocks, subtracts L_ik L_jk^T for each k left of it with
  // L_jk != 0, factors its diagonal block and solves its column against it.
  bool factorize(const double* blocks) {
    std::fill(diagonal.begin(), diagonal.end(), 0.0);
    std::fill(lower.begin(), lower.end(), 0.0);
    for (size_t k = 0; k < target.size(); ++k) {
      if (target[k] == kSkip) continue;
      double* to = target[k] >= 0 ? &lower[static_cast<size_t>(kBlock) * target[k]]
                                  : &diagonal[static_cast<size_t>(kBlock) * (-1 - target[k])];
      const double* from = blocks + kBlock * k;
      for (int e = 0; e < kBlock; ++e) to[e] += from[e];
    }
    for (int j = 0; j < handles; ++j) {
      for (int s = colStart[j]; s < colStart[j + 1]; ++s) slotOfRow[rows[s]] = s;
      BlockMap d(&diagonal[static_cast<size_t>(kBlock) * j]);
      for (int q = rowListStart[j]; q < rowListStart[j + 1]; ++q) {
        const int k = rowListColumn[q], slotJ = rowListSlot[q];
        const ConstBlockMap ljk(&lower[static_cast<size_t>(kBlock) * slotJ]);
        d.noalias() -= ljk * ljk.transpose();
        for (int s = slotJ + 1; s < colStart[k + 1]; ++s) {
          BlockMap w(&lower[static_cast<size_t>(kBlock) * slotOfRow[rows[s]]]);
          w.noalias() -= ConstBlockMap(&lower[static_cast<size_t>(kBlock) * s]) * ljk.transpose();
        }
      }
      for (int s = colStart[j]; s < colStart[j + 1]; ++s) slotOfRow[rows[s]] = -1;
      Eigen::LLT<Eigen::Ref<Block>> llt(d);  // in place: d becomes L_jj (lower triangle)
      if (llt.info() != Eigen::Success || !d.allFinite()) return false;
      d.triangularView<Eigen::StrictlyUpper>().setZero();
      for (int s = colStart[j]; s < colStart[j + 1]; ++s) {
        BlockMap w(&lower[static_cast<size_t>(kBlock) * s]);
        d.transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(w);
      }
    }
    return true;
  }

  void solve(double* x) const {
    y.resize(12 * static_cast<size_t>(handles));
    for (int j = 0; j < handles; ++j)
      std::copy(x + 12 * order[j], x + 12 * order[j] + 12, y.begin() + 12 * j);
    for (int j = 0; j < handles; ++j) {
      Segment yj(&y[12 * j]);
      ConstBlockMap(&diagonal[static_cast<size_t>(kBlock) * j])
          .triangularView<Eigen::Lower>()
          .solveInPlace(yj);
      for (int s = colStart[j]; s < colStart[j + 1]; ++s)
        Segment(&y[12 * rows[s]]).noalias() -=
            ConstBlockMap(&lower[static_cast<size_t>(kBlock) * s]) * yj;
    }
    for (int j = handles - 1; j >= 0; --j) {
      Segment yj(&y[12 * j]);
      for (int s = colStart[j]; s < colStart[j + 1]; ++s)
        yj.noalias() -= ConstBlockMap(&lower[static_cast<size_t>(kBlock) * s]).transpose() *
                        Segment(&y[12 * rows[s]]);
      ConstBlockMap(&diagonal[static_cast<size_t>(kBlock) * j])
          .transpose()
          .triangularView<Eigen::Upper>()
          .solveInPlace(yj);
    }
    for (int j = 0; j < handles; ++j)
      std::copy(y.begin() + 12 * j, y.begin() + 12 * j + 12, x + 12 * order[j]);
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
  return m.factorize(blocks);
}

void CoarseCholesky::solve(double* x) const {
  impl_->solve(x);
}

}  // namespace galsculpt
