// MultigridCycle's smoothers and coarsest solve (multigrid_cycle.h): Gauss-Seidel by colours or
// weighted Jacobi on the fine and coarse levels, and the coarsest level's Cholesky or CG.
// Included by multigrid_cycle.h only, after the class.
#pragma once

#include "solver/multigrid/multigrid_cycle.h"

namespace galsculpt {

template <typename Exec>
void MultigridCycle<Exec>::smoothFine(const double* a, const double* b, double* x, int sweeps,
                                      bool reverse, const Settings& s) {
  const int* rowStart = smoother_.rowStart();
  const int* columns = smoother_.columns();
  const int* source = smoother_.source();
  const float* single = smoother_.singleBlocks();
  const bool inFloat = smoother_.single();
  const double* inverse = smoother_.diagonalInverse();
  const int* rowOf = fineColorRows_.data();
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    if (jacobi(s)) {
      double* ax = ax_.data();
      multiplySmoother(a, x, ax);
      const double w = kJacobiWeight;
      ex_.forEach(
          rows_,
          [=] GALSCULPT_LAMBDA(int i) {
            const int r = rowOf[i];
            double res[3], dx[3];
            for (int k = 0; k < 3; ++k) res[k] = b[3 * r + k] - ax[3 * r + k];
            multiply3(inverse + 9 * i, res, dx);
            for (int k = 0; k < 3; ++k) x[3 * r + k] += w * dx[k];
          },
          16);
      continue;
    }
    if constexpr (Exec::kHostMemory) {
      const fine_rows::SweepRow row = inFloat ? fine_rows::sweepRow() : nullptr;
      if (row) {
        const fine_rows::Rows m = smoother_.hostRows(rowOf);
        forEachColour(
            fineColorStart_, reverse, [=](int i) { row(m, i, b, x); },
            FineSmoother<Exec>::kRowCost);
        continue;
      }
    }
    forEachColour(
        fineColorStart_, reverse,
        [=] GALSCULPT_LAMBDA(int i) {
          const int r = rowOf[i];
          double rhs[3] = {b[3 * r], b[3 * r + 1], b[3 * r + 2]};
          for (int k = rowStart[i]; k < rowStart[i + 1]; ++k) {
            if (inFloat)
              subtractMultiply3(single + 9 * static_cast<size_t>(k), x + 3 * columns[k], rhs);
            else
              subtractMultiply3(a + 9 * static_cast<size_t>(source[k]), x + 3 * columns[k], rhs);
          }
          multiply3(inverse + 9 * i, rhs, x + 3 * r);
        },
        FineSmoother<Exec>::kRowCost);
  }
}

template <typename Exec>
void MultigridCycle<Exec>::smoothCoarse(int l, const double* b, double* x, int sweeps, bool reverse,
                                        const Settings& s) {
  Level& d = levels_[l - 1];
  const int* rowStart = d.rowStart.data();
  const int* columns = d.columns.data();
  const double* blocks = d.blocks.data();
  const double* factor = d.diagonalFactor.data();
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    if (jacobi(s)) {
      double* ax = d.ax.data();
      multiplyCoarse(l - 1, x, ax);
      const double w = kJacobiWeight;
      ex_.forEach(
          d.handles,
          [=] GALSCULPT_LAMBDA(int r) {
            double res[12];
            for (int i = 0; i < 12; ++i) res[i] = b[12 * r + i] - ax[12 * r + i];
            choleskySolve(12, factor + 144 * r, res);
            for (int i = 0; i < 12; ++i) x[12 * r + i] += w * res[i];
          },
          300);
      continue;
    }
    const int* colorRows = d.colorRows.data();
    forEachColour(
        d.colorStart, reverse,
        [=] GALSCULPT_LAMBDA(int i) {
          const int r = colorRows[i];
          double rhs[12];
          for (int j = 0; j < 12; ++j) rhs[j] = b[12 * r + j];
          for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
            if (columns[k] == r) continue;
            double t[12] = {};
            addMultiply12(blocks + 144 * k, x + 12 * columns[k], t);
            for (int j = 0; j < 12; ++j) rhs[j] -= t[j];
          }
          choleskySolve(12, factor + 144 * r, rhs);
          for (int j = 0; j < 12; ++j) x[12 * r + j] = rhs[j];
        },
        d.rowCost);
  }
}

template <typename Exec>
void MultigridCycle<Exec>::solveCoarsest(const double* b, double* x, const Settings& s) {
  const Level& c = levels_.back();
  const int n = 12 * c.handles;
  if (s.coarseSolver == CoarseSolver::Cholesky && factored_) {
    if constexpr (Exec::kHostMemory) {
      ex_.copy(x, b, n);
      sparse_->solve(x);
    } else {
      const double* inverse = dense_.inverse.data();
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
        double acc = 0.0;
        for (int j = 0; j < n; ++j) acc += inverse[i + static_cast<size_t>(n) * j] * b[j];
        x[i] = acc;
      });
    }
    return;
  }
  // CG for a fixed number of iterations; with pieces, from the exact per-piece affine
  // solution. Its stopping tests are device scalars read by the launches that follow.
  double* r = cgR_.data();
  double* p = cgP_.data();
  double* ap = cgAp_.data();
  double* sc = scalars_.data();
  ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
    x[i] = 0.0;
    r[i] = b[i];
  });
  if (pieces_.active()) startFromPieces(b, x);
  ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) { p[i] = r[i]; });
  ex_.sum(
      n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * r[i]; }, sc + kRr);
  ex_.sum(
      n, [=] GALSCULPT_LAMBDA(int i) { return b[i] * b[i]; }, sc + kBB);
  ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
    sc[kStop] = 1e-30 * fmax(sc[kBB], 1e-300);
    sc[kDone] = 0.0;
  });
  // Each launch of an iteration decides alone whether the iteration is live, from scalars no
  // launch of that iteration writes before the last one: 3 launches and 2 reductions each.
  for (int it = 0; it < s.coarseIterations; ++it) {
    multiplyCoarse(numLevels() - 1, p, ap);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return p[i] * ap[i]; }, sc + kPap);
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
      if (!cgLive(sc)) return;
      const double alpha = sc[kRr] / sc[kPap];
      x[i] += alpha * p[i];
      r[i] -= alpha * ap[i];
    });
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * r[i]; }, sc + kRrNew);
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
      if (cgLive(sc)) p[i] = r[i] + (sc[kRrNew] / sc[kRr]) * p[i];
    });
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      if (cgLive(sc)) {
        sc[kRr] = sc[kRrNew];
      } else {
        sc[kDone] = 1.0;  // stopped for good: the later launches do nothing
      }
    });
  }
}

}  // namespace galsculpt
