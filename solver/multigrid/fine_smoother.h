// The fine level's smoother operator for the Galerkin multigrid's V-cycle (multigrid_cycle.h):
// the fine rows in colour order (so that a colour's sweep streams through its own rows), each
// row's off-diagonal blocks with their columns and the fine blocks they copy, and the inverses
// of the diagonal blocks. With a single-precision refresh (the V-cycle only preconditions CG) the
// off-diagonal blocks are also kept rounded to float, which halves what every sweep reads.
#pragma once

#include <cstddef>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/fem/dense_kernels.h"
#include "solver/fem/kernel_math.h"
#include "solver/multigrid/fine_rows.h"

namespace galsculpt {

template <typename Exec>
class FineSmoother {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  // Work of one smoother row (about 14 blocks) for the CPU executor's threading.
  static constexpr long kRowCost = 16;

  explicit FineSmoother(Exec& ex) : ex_(ex) {}

  // The pattern: row i of the colour order is fine row colorRows[i] of `fine`.
  void uploadPattern(const BlockPattern& fine, const std::vector<int>& colorRows) {
    std::vector<int> rowStart(1, 0), columns, source;
    columns.reserve(fine.columns.size());
    source.reserve(fine.columns.size());
    for (const int r : colorRows) {
      for (int k = fine.rowStart[r]; k < fine.rowStart[r + 1]; ++k) {
        if (fine.columns[k] == r) continue;
        columns.push_back(fine.columns[k]);
        source.push_back(k);
      }
      rowStart.push_back(static_cast<int>(columns.size()));
    }
    rows_ = static_cast<int>(colorRows.size());
    nnz_ = static_cast<int>(columns.size());
    rowStart_.upload(rowStart);
    columns_.upload(columns);
    source_.upload(source);
    blocks_.resize(9 * static_cast<size_t>(nnz_));
    diagonalInverse_.resize(9 * static_cast<size_t>(rows_));
  }

  // The inverses of the diagonal blocks of `a` in colour order (the arithmetic of solve3), and
  // with `single` the off-diagonal blocks rounded to float. `rowOf`: the colour order's rows;
  // `diagonalBlock`: the fine pattern's diagonal block of each row.
  void refresh(const double* a, bool single, const int* rowOf, const int* diagonalBlock) {
    single_ = single;
    if (single) {
      const int* source = source_.data();
      float* blocks = blocks_.data();
      ex_.forEach(nnz_, [=] GALSCULPT_LAMBDA(int k) {
        const double* from = a + 9 * static_cast<size_t>(source[k]);
        for (int i = 0; i < 9; ++i)
          blocks[9 * static_cast<size_t>(k) + i] = static_cast<float>(from[i]);
      });
    }
    double* inverse = diagonalInverse_.data();
    ex_.forEach(
        rows_,
        [=] GALSCULPT_LAMBDA(int i) {
          kernels::M3 m;
          const double* from = a + 9 * static_cast<size_t>(diagonalBlock[rowOf[i]]);
          for (int k = 0; k < 9; ++k) m.a[k] = from[k];
          const kernels::M3 inv = kernels::inverse(m);
          for (int k = 0; k < 9; ++k) inverse[9 * i + k] = inv.a[k];
        },
        16);
  }

  // y = A x with the float copy (single() only): the diagonal blocks from `a`.
  void multiplySingle(const double* a, const double* x, double* y, const int* rowOf,
                      const int* diagonal) {
    const int* rowStart = rowStart_.data();
    const int* columns = columns_.data();
    const float* blocks = blocks_.data();
    if constexpr (Exec::kHostMemory) {
      if (const fine_rows::ProductRow row = fine_rows::productRow()) {
        const fine_rows::Rows m = hostRows(rowOf);
        ex_.forEach(
            rows_, [=](int i) { row(m, i, a + 9 * static_cast<size_t>(diagonal[rowOf[i]]), x, y); },
            kRowCost);
        return;
      }
    }
    ex_.forEach(
        rows_,
        [=] GALSCULPT_LAMBDA(int i) {
          const int r = rowOf[i];
          double acc[3];
          multiply3(a + 9 * static_cast<size_t>(diagonal[r]), x + 3 * r, acc);
          for (int k = 0; k < 3; ++k) acc[k] = -acc[k];
          for (int k = rowStart[i]; k < rowStart[i + 1]; ++k)
            subtractMultiply3(blocks + 9 * static_cast<size_t>(k), x + 3 * columns[k], acc);
          for (int k = 0; k < 3; ++k) y[3 * r + k] = -acc[k];
        },
        kRowCost);
  }

  // The operator for fine_rows.h's kernels (host memory, after a single-precision refresh).
  fine_rows::Rows hostRows(const int* rowOf) const {
    return {rowStart_.data(), columns_.data(), blocks_.data(), diagonalInverse_.data(), rowOf};
  }

  bool single() const { return single_; }
  const int* rowStart() const { return rowStart_.data(); }
  const int* columns() const { return columns_.data(); }
  const int* source() const { return source_.data(); }  // the fine block each entry copies
  const float* singleBlocks() const { return blocks_.data(); }
  const double* diagonalInverse() const { return diagonalInverse_.data(); }

 private:
  Exec& ex_;
  int rows_ = 0, nnz_ = 0;
  bool single_ = false;
  Buffer<int> rowStart_, columns_, source_;
  Buffer<float> blocks_;
  Buffer<double> diagonalInverse_;
};

}  // namespace galsculpt
