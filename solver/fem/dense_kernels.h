// Small dense linear algebra for the multigrid cycle on either executor (12x12 handle blocks, 3x3
// vertex blocks), __host__ __device__: one thread factors or solves one block. Column-major.
#pragma once

#include <cmath>

#include "solver/fem/element_kernels.h"

#if defined(__CUDACC__)
#define GALSCULPT_LAMBDA __host__ __device__
#else
#define GALSCULPT_LAMBDA
#endif

namespace galsculpt {

// y = A x for a 3x3 block.
GALSCULPT_HD void multiply3(const double* a, const double* x, double* y) {
  for (int r = 0; r < 3; ++r) y[r] = a[r] * x[0] + a[r + 3] * x[1] + a[r + 6] * x[2];
}

// y -= A x for a 3x3 block.
GALSCULPT_HD void subtractMultiply3(const double* a, const double* x, double* y) {
  for (int r = 0; r < 3; ++r) y[r] -= a[r] * x[0] + a[r + 3] * x[1] + a[r + 6] * x[2];
}

// y -= A x for a 3x3 block stored in single precision (the fine smoother's copy).
GALSCULPT_HD void subtractMultiply3(const float* a, const double* x, double* y) {
  for (int r = 0; r < 3; ++r) y[r] -= a[r] * x[0] + a[r + 3] * x[1] + a[r + 6] * x[2];
}

// x = A^-1 b through the cofactors (the CPU smoother's Matrix3d::inverse()).
GALSCULPT_HD void solve3(const double* a, const double* b, double* x) {
  kernels::M3 m;
  for (int i = 0; i < 9; ++i) m.a[i] = a[i];
  const kernels::M3 inv = kernels::inverse(m);
  multiply3(inv.a, b, x);
}

using kernels::cholesky;
using kernels::choleskySolve;

// LDL^T with symmetric pivoting (the largest remaining diagonal first, as Eigen's LDLT) of a
// 12x12 block, in place: L below the diagonal, D on it, the pivots in perm. False when NaN.
GALSCULPT_HD bool ldlt12(double* a, int* perm) {
  constexpr int n = 12;
  for (int i = 0; i < n; ++i) perm[i] = i;
  for (int j = 0; j < n; ++j) {
    int p = j;
    for (int i = j + 1; i < n; ++i)
      if (fabs(a[i + n * i]) > fabs(a[p + n * p])) p = i;
    if (p != j) {
      // Symmetric swap of rows and columns j and p (only the lower triangle is used).
      for (int k = 0; k < n; ++k) {
        double t = a[j + n * k];
        a[j + n * k] = a[p + n * k];
        a[p + n * k] = t;
      }
      for (int k = 0; k < n; ++k) {
        double t = a[k + n * j];
        a[k + n * j] = a[k + n * p];
        a[k + n * p] = t;
      }
      const int t = perm[j];
      perm[j] = perm[p];
      perm[p] = t;
    }
    const double d = a[j + n * j];
    if (!(d == d)) return false;
    double c[n];  // the pivot column before scaling
    for (int i = j + 1; i < n; ++i) c[i] = a[i + n * j];
    for (int i = j + 1; i < n; ++i) {
      const double lij = d != 0.0 ? c[i] / d : 0.0;
      for (int k = j + 1; k <= i; ++k) {
        a[i + n * k] -= lij * c[k];
        a[k + n * i] = a[i + n * k];  // the upper triangle in step, for later swaps
      }
      a[i + n * j] = lij;
    }
  }
  return true;
}

// Solves with an ldlt12 factorization: x = P^T L^-T D^-1 L^-1 P b.
GALSCULPT_HD void ldlt12Solve(const double* a, const int* perm, const double* b, double* x) {
  constexpr int n = 12;
  double y[n];
  for (int i = 0; i < n; ++i) y[i] = b[perm[i]];
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < i; ++k) y[i] -= a[i + n * k] * y[k];
  for (int i = 0; i < n; ++i) y[i] = a[i + n * i] != 0.0 ? y[i] / a[i + n * i] : 0.0;
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k < n; ++k) y[i] -= a[k + n * i] * y[k];
  for (int i = 0; i < n; ++i) x[perm[i]] = y[i];
}

// The Galerkin blocks of a fine row's blocks A_c (3x3) with affine modes (yr, yc: 4 each), sum
// over c of (yr yc^T) kron A_c, in two steps: row (3x12, row[r + 3 (3 j + c)]) += A_c yc_j for
// each column vertex, then out += (yr_i row) for the row's modes once: a quarter of the
// multiply-adds of each block's Kronecker product once a row has four blocks.
GALSCULPT_HD void addBlockTimesModes(const double* yc, const double* a, double* row) {
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) row[r + 3 * (3 * j + c)] += yc[j] * a[r + 3 * c];
}
GALSCULPT_HD void addModesTimesRow(const double* yr, const double* row, double* out) {
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 4; ++i)
        for (int r = 0; r < 3; ++r)
          out[(3 * i + r) + 12 * (3 * j + c)] += yr[i] * row[r + 3 * (3 * j + c)];
}

// A Galerkin product of 12x12 blocks in two steps, for a finer row's blocks B_c: sum += B_c T_c
// for each, then out += T_r^T sum once.
GALSCULPT_HD void addProduct12(const double* b, const double* tc, double* sum) {
  for (int c = 0; c < 12; ++c)
    for (int r = 0; r < 12; ++r) {
      double s = 0.0;
      for (int k = 0; k < 12; ++k) s += b[r + 12 * k] * tc[k + 12 * c];
      sum[r + 12 * c] += s;
    }
}
GALSCULPT_HD void addTransposedProduct12(const double* tr, const double* sum, double* out) {
  for (int c = 0; c < 12; ++c)
    for (int r = 0; r < 12; ++r) {
      double s = 0.0;
      for (int k = 0; k < 12; ++k) s += tr[k + 12 * r] * sum[k + 12 * c];
      out[r + 12 * c] += s;
    }
}

// out += T_r^T B T_c for 12x12 blocks (one block: the two steps above).
GALSCULPT_HD void addTripleProduct12(const double* tr, const double* b, const double* tc,
                                     double* out) {
  double bt[144];  // B T_c
  for (double& v : bt) v = 0.0;
  addProduct12(b, tc, bt);
  addTransposedProduct12(tr, bt, out);
}

// y (+)= A x for 12x12 blocks; transposed: y += A^T x.
GALSCULPT_HD void addMultiply12(const double* a, const double* x, double* y) {
  for (int c = 0; c < 12; ++c)
    for (int r = 0; r < 12; ++r) y[r] += a[r + 12 * c] * x[c];
}
GALSCULPT_HD void addMultiplyTransposed12(const double* a, const double* x, double* y) {
  for (int c = 0; c < 12; ++c) {
    double s = 0.0;
    for (int r = 0; r < 12; ++r) s += a[r + 12 * c] * x[r];
    y[c] += s;
  }
}

}  // namespace galsculpt
