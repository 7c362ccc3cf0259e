// MultigridCycle::refresh (multigrid_cycle.h): the Galerkin products A_{l+1} = U^T A_l U from the
// fine matrix down, the smoothers' factors and the coarsest level's factorization. Included by
// multigrid_cycle.h only, after the class.
#pragma once

#include "solver/multigrid/multigrid_cycle.h"

namespace galsculpt {

template <typename Exec>
void MultigridCycle<Exec>::refresh(const double* fine, bool coarseCholesky, bool preconditions) {
  smoother_.refresh(fine, preconditions, fineColorRows_.data(), fineDiagonal_.data());
  for (size_t l = 0; l < levels_.size(); ++l) {
    Level& d = levels_[l];
    const double* finer = l == 0 ? fine : levels_[l - 1].blocks.data();
    const int* finerColumns = l == 0 ? fineColumns_.data() : levels_[l - 1].columns.data();
    const double* y = d.y.data();
    const double* toParent = d.toParent.data();
    const int* start = d.contribStart.data();
    const int* block = d.contribBlock.data();
    const int* row = d.contribRow.data();
    double* out = d.blocks.data();
    const bool first = l == 0;
    const std::uint8_t* fixed = fixed_;
    if constexpr (!Exec::kHostMemory) {
      galerkinByEntries(d.nnz, start, block, row, finerColumns, first, fixed, y, toParent, finer,
                        out);
    } else {
      // A block's terms come finer row by finer row (multigrid_layout.h): each row's blocks
      // times their columns' modes are summed first, then taken into the row's modes once
      // (addBlockTimesModes, addTransposedProduct12), not each block on both sides.
      ex_.forEach(
          d.nnz,
          [=] GALSCULPT_LAMBDA(int b) {
            double acc[144];
            for (double& a : acc) a = 0.0;
            double rowSum[144];
            for (int i = start[b]; i < start[b + 1];) {
              const int r = row[i];
              int end = i + 1;
              while (end < start[b + 1] && row[end] == r) ++end;
              if (first) {
                if (!(fixed && fixed[r])) {
                  for (int e = 0; e < 36; ++e) rowSum[e] = 0.0;
                  for (int q = i; q < end; ++q) {
                    const int k = block[q], c = finerColumns[k];
                    if (!(fixed && fixed[c])) addBlockTimesModes(y + 4 * c, finer + 9 * k, rowSum);
                  }
                  addModesTimesRow(y + 4 * r, rowSum, acc);
                }
              } else {
                for (double& e : rowSum) e = 0.0;
                for (int q = i; q < end; ++q) {
                  const int k = block[q];
                  addProduct12(finer + 144 * k, toParent + 144 * finerColumns[k], rowSum);
                }
                addTransposedProduct12(toParent + 144 * r, rowSum, acc);
              }
              i = end;
            }
            for (int i = 0; i < 144; ++i) out[144 * b + i] = acc[i];
          },
          d.refreshCost);
    }
    // Modes no fine vertex sees: a relative shift (identity for a handle without rows).
    const int* diagonal = d.diagonal.data();
    const std::uint8_t* empty = d.empty.data();
    double* factor = d.diagonalFactor.data();
    ex_.forEach(
        d.handles,
        [=] GALSCULPT_LAMBDA(int h) {
          double* blk = out + 144 * diagonal[h];
          double trace = 0.0;
          for (int i = 0; i < 12; ++i) trace += blk[13 * i];
          // A handle whose rows are all anchored sees nothing either.
          const double shift = empty[h] || !(trace > 0.0) ? 1.0 : 1e-9 * trace / 12.0;
          for (int i = 0; i < 12; ++i) blk[13 * i] += shift;
          double* f = factor + 144 * h;
          for (int i = 0; i < 144; ++i) f[i] = blk[i];
          cholesky(12, f);
        },
        1000);
  }
  if (fragments_.fragments() > 0)
    fragments_.factorize(fine, fineRowStart_.data(), fineColumns_.data());
  if (pieces_.active())
    pieces_.factorize(levels_.back().columns.data(), levels_.back().blocks.data());
  if (!coarseCholesky) {
    factored_ = false;
    return;
  }
  const Level& c = levels_.back();
  if constexpr (Exec::kHostMemory) {
    if (!adopted_.empty()) {
      // Only a matrix of this hierarchy's pattern: one saved under other damage is dropped.
      if (adopted_.size() == c.blocks.size()) {
        if (!sparse_) sparse_ = std::make_unique<CoarseCholesky>();
        factored_ =
            sparse_->factor(c.handles, c.rowStart.data(), c.columns.data(), adopted_.data());
        kept_.remember(factored_, adopted_.data(), adopted_.size(), c.diagonal.data(), c.handles);
      }
      adopted_.clear();
    }
    if (preconditions && factored_ &&
        kept_.keeps(c.blocks.data(), c.blocks.size(), c.rowStart.data(), c.columns.data(),
                    c.handles)) {
      ++coarseFactorsKept_;
      return;
    }
  }
  factored_ = false;
  // In host memory by 12x12 blocks along the handle graph, whatever its size
  // (coarse_cholesky.h); a device factors the dense matrix.
  if constexpr (Exec::kHostMemory) {
    if (!sparse_) sparse_ = std::make_unique<CoarseCholesky>();
    factored_ = sparse_->factor(c.handles, c.rowStart.data(), c.columns.data(), c.blocks.data());
    rememberFactored(c);
    return;
  }
  // Allocated once a size (each entry is written below): an allocation ends the device program.
  const size_t entries = static_cast<size_t>(dense_.size) * dense_.size;
  if (dense_.factor.size() != entries) dense_.factor.resize(entries);
  if (dense_.inverse.size() != entries) dense_.inverse.resize(entries);
  double* dense = dense_.factor.data();
  const double* blocks = c.blocks.data();
  const int* rowStart = c.rowStart.data();
  const int* columns = c.columns.data();
  const int n = dense_.size;
  ex_.forEach(n * n, [=] GALSCULPT_LAMBDA(int i) { dense[i] = 0.0; });
  // A thread per row of the dense matrix (twelve per handle: a handle's thread wrote 1,500
  // entries serially on a device).
  ex_.forEach(12 * c.handles, [=] GALSCULPT_LAMBDA(int e) {
    const int r = e / 12, i = e % 12;
    for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
      const int col = columns[k];
      for (int j = 0; j < 12; ++j)
        dense[e + static_cast<size_t>(n) * (12 * col + j)] = blocks[144 * k + i + 12 * j];
    }
  });
  // Its status is not waited for: it goes to the scalars, and the Newton iteration's read
  // brings it (coarseFailure); a failure there solves the step again with the coarse CG.
  factored_ = ex_.denseCholesky(n, dense, scalars_.data() + kFactorFailed);
  dense_.statusPending = factored_;
  if (!factored_) return;
  // The coarsest solve a V-cycle makes is then one product with the inverse: a phase of the
  // device program that runs PCG (a triangular solve is n steps of its own, and cuSOLVER's would
  // end the program). Symmetrized, so that the preconditioner stays symmetric.
  double* inverse = dense_.inverse.data();
  ex_.denseCholeskyInverse(n, dense, inverse);
  ex_.forEach(n * n, [=] GALSCULPT_LAMBDA(int e) {
    const int i = e % n, j = e / n;
    if (i > j) {
      const double mean = 0.5 * (inverse[e] + inverse[j + static_cast<size_t>(n) * i]);
      inverse[e] = mean;
      inverse[j + static_cast<size_t>(n) * i] = mean;
    }
  });
}

template <typename Exec>
void MultigridCycle<Exec>::galerkinByEntries(int nnz, const int* start, const int* block,
                                             const int* row, const int* finerColumns, bool first,
                                             const std::uint8_t* fixed, const double* y,
                                             const double* toParent, const double* finer,
                                             double* out) {
  if (first) {
    ex_.forEach(144 * nnz, [=] GALSCULPT_LAMBDA(int e) {
      const int b = e / 144, entry = e % 144;
      const int rowIn = entry % 12, colIn = entry / 12;  // (3 i + r, 3 j + c)
      const int i = rowIn / 3, r = rowIn % 3, j = colIn / 3, c = colIn % 3;
      double acc = 0.0;
      for (int q = start[b]; q < start[b + 1];) {
        const int vr = row[q];
        double sum = 0.0;  // the finer row's blocks times their columns' modes
        for (; q < start[b + 1] && row[q] == vr; ++q) {
          const int k = block[q], vc = finerColumns[k];
          if (!(fixed && fixed[vc])) sum += y[4 * vc + j] * finer[9 * k + r + 3 * c];
        }
        if (!(fixed && fixed[vr])) acc += y[4 * vr + i] * sum;
      }
      out[e] = acc;
    });
    return;
  }
  ex_.forEach(12 * nnz, [=] GALSCULPT_LAMBDA(int e) {
    const int b = e / 12, c = e % 12;  // a column of the block
    double acc[12];
    for (double& a : acc) a = 0.0;
    for (int q = start[b]; q < start[b + 1];) {
      const int vr = row[q];
      double bt[12];  // column c of the finer row's sum of B T_c
      for (double& v : bt) v = 0.0;
      for (; q < start[b + 1] && row[q] == vr; ++q) {
        const int k = block[q];
        const double* bk = finer + 144 * k;
        const double* tc = toParent + 144 * finerColumns[k] + 12 * c;
        for (int r = 0; r < 12; ++r) {
          double sum = 0.0;
          for (int m = 0; m < 12; ++m) sum += bk[r + 12 * m] * tc[m];
          bt[r] += sum;
        }
      }
      const double* tr = toParent + 144 * vr;
      for (int r = 0; r < 12; ++r) {
        double sum = 0.0;
        for (int m = 0; m < 12; ++m) sum += tr[m + 12 * r] * bt[m];
        acc[r] += sum;
      }
    }
    for (int r = 0; r < 12; ++r) out[144 * b + r + 12 * c] = acc[r];
  });
}

}  // namespace galsculpt
