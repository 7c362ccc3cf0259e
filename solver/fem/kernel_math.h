// The small dense linear algebra of the element kernels in plain arrays, compiled for the CPU and
// the GPU: 3x3 matrices (column-major, as Eigen stores them), a 6x6 inverse, symmetric
// eigen-solves (cyclic Jacobi, robust for repeated and zero eigenvalues, and a closed form used
// where it is accurate) and the rotation-variant SVD of a deformation gradient.
//
// Header only, no Eigen, no exceptions, no allocation: every function is __host__ __device__
// under nvcc.
#pragma once

#include <cmath>

#include "solver/fem/eigen_svd.h"
#include "solver/fem/host_device.h"

namespace galsculpt::kernels {

struct M3 {
  double a[9];  // column-major
  GALSCULPT_HD double& operator()(int r, int c) { return a[r + 3 * c]; }
  GALSCULPT_HD double operator()(int r, int c) const { return a[r + 3 * c]; }
};

GALSCULPT_HD M3 identity3() {
  M3 m{};
  m(0, 0) = m(1, 1) = m(2, 2) = 1.0;
  return m;
}

GALSCULPT_HD M3 multiply(const M3& x, const M3& y) {
  M3 m{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m(r, c) = x(r, 0) * y(0, c) + x(r, 1) * y(1, c) + x(r, 2) * y(2, c);
  return m;
}

GALSCULPT_HD M3 transpose(const M3& x) {
  M3 m{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m(r, c) = x(c, r);
  return m;
}

GALSCULPT_HD double determinant(const M3& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(2, 1) * m(1, 2)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(2, 0) * m(1, 2)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(2, 0) * m(1, 1));
}

// Columns of the cofactor matrix (dJ/dF): cross products of F's other two columns.
GALSCULPT_HD M3 cofactor(const M3& f) {
  M3 c{};
  for (int j = 0; j < 3; ++j) {
    const int p = (j + 1) % 3, q = (j + 2) % 3;
    c(0, j) = f(1, p) * f(2, q) - f(2, p) * f(1, q);
    c(1, j) = f(2, p) * f(0, q) - f(0, p) * f(2, q);
    c(2, j) = f(0, p) * f(1, q) - f(1, p) * f(0, q);
  }
  return c;
}

// Inverse through the cofactors; the caller checks the determinant.
GALSCULPT_HD M3 inverse(const M3& m) {
  const M3 c = cofactor(m);
  const double det = determinant(m);
  M3 inv{};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) inv(r, k) = c(k, r) / det;
  return inv;
}

GALSCULPT_HD double squaredNorm(const M3& m) {
  double s = 0.0;
  for (double v : m.a) s += v * v;
  return s;
}

GALSCULPT_HD double maxAbs(const M3& m) {
  double s = 0.0;
  for (double v : m.a) s = fmax(s, fabs(v));
  return s;
}

// Gauss-Jordan inverse of a 6x6 column-major matrix with partial pivoting; false when singular.
GALSCULPT_HD bool invert6(const double in[36], double out[36]) {
  double a[6][12];
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) {
      a[r][c] = in[r + 6 * c];
      a[r][c + 6] = r == c ? 1.0 : 0.0;
    }
  for (int col = 0; col < 6; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 6; ++r)
      if (fabs(a[r][col]) > fabs(a[pivot][col])) pivot = r;
    if (!(fabs(a[pivot][col]) > 0.0)) return false;
    if (pivot != col)
      for (int c = 0; c < 12; ++c) {
        const double t = a[col][c];
        a[col][c] = a[pivot][c];
        a[pivot][c] = t;
      }
    const double inv = 1.0 / a[col][col];
    for (int c = 0; c < 12; ++c) a[col][c] *= inv;
    for (int r = 0; r < 6; ++r) {
      if (r == col || a[r][col] == 0.0) continue;
      const double factor = a[r][col];
      for (int c = 0; c < 12; ++c) a[r][c] -= factor * a[col][c];
    }
  }
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) out[r + 6 * c] = a[r][c + 6];
  return true;
}

// U diag(d) V^T.
GALSCULPT_HD M3 scaledProduct(const M3& u, const double d[3], const M3& v) {
  return scaledProductOf(u, d, v);
}

// The eigen-solves and the SVD below are eigen_svd.h's, instantiated for double (the SIMD lanes
// instantiate the same source on their lane type).

// Symmetric eigen-solve of a 3x3 matrix by cyclic Jacobi: a = q diag(w) q^T, q a rotation.
// Accurate for repeated eigenvalues (where closed forms lose orthogonality).
GALSCULPT_HD void symmetricEigen(const M3& input, double w[3], M3& q) {
  jacobiEigenOf<ScalarMath>(input, w, q, true);
}

// The eigenvalues of a symmetric matrix a in closed form (Cardano's trigonometric roots):
// shift + scale t_i, t the roots of b = (a - shift I) / scale (trace 0, largest entry 1), t[0]
// the smallest and t[2] the largest. scale 0: a = shift I (t zero). False for a NaN entry.
using CardanoRoots = CardanoRootsOf<double, M3>;

GALSCULPT_HD bool cardanoRoots(const M3& a, CardanoRoots& r) {
  return cardanoRootsOf<ScalarMath>(a, r);
}

// The same eigen-solve in closed form, several times cheaper than Jacobi; false where it is not
// accurate (nearly repeated eigenvalues), checked by the reconstruction |q diag(w) q^T - a|.
GALSCULPT_HD bool closedFormSymmetricEigen(const M3& a, double w[3], M3& q) {
  return closedFormEigenOf<ScalarMath>(a, w, q);
}

// Closed form where accurate, Jacobi otherwise.
GALSCULPT_HD void fastSymmetricEigen(const M3& a, double w[3], M3& q) {
  fastEigenOf<ScalarMath>(a, w, q, true);
}

// F = U diag(s) V^T with U, V rotations, s sorted by magnitude of the first two, s[2] < 0 when
// F is inverted (the rotation-variant SVD of Irving et al.).
// `accurate`: Jacobi for V; otherwise the closed form where it reconstructs F^T F. Returns the
// largest part of F V that the factors drop (zero in exact arithmetic).
GALSCULPT_HD double svdFromNormalMatrix(const M3& f, bool accurate, M3& u, double s[3], M3& v) {
  double w[3];
  M3 q;
  if (accurate) {
    symmetricEigen(multiply(transpose(f), f), w, q);
    // One-sided Jacobi on the columns of F q: F^T F loses the small singular values (their
    // squares drown in round-off), orthogonalizing F's own columns keeps them accurate.
    M3 b = multiply(f, q);
    for (int sweep = 0; sweep < 16; ++sweep) {
      bool rotated = false;
      for (int pair = 0; pair < 3; ++pair) {
        const int i = pair == 2 ? 1 : 0, j = pair == 0 ? 1 : 2;
        double alpha = 0.0, beta = 0.0, gamma = 0.0;
        for (int r = 0; r < 3; ++r) {
          alpha += b(r, i) * b(r, i);
          beta += b(r, j) * b(r, j);
          gamma += b(r, i) * b(r, j);
        }
        if (!(fabs(gamma) > 1e-17 * sqrt(alpha * beta)) || gamma == 0.0) continue;
        rotated = true;
        const double zeta = (beta - alpha) / (2.0 * gamma);
        const double t = (zeta >= 0.0 ? 1.0 : -1.0) / (fabs(zeta) + sqrt(1.0 + zeta * zeta));
        const double c = 1.0 / sqrt(1.0 + t * t), sn = c * t;
        for (int r = 0; r < 3; ++r) {
          const double bi = b(r, i), bj = b(r, j), qi = q(r, i), qj = q(r, j);
          b(r, i) = c * bi - sn * bj;
          b(r, j) = sn * bi + c * bj;
          q(r, i) = c * qi - sn * qj;
          q(r, j) = sn * qi + c * qj;
        }
      }
      if (!rotated) break;
    }
    for (int i = 0; i < 3; ++i) w[i] = b(0, i) * b(0, i) + b(1, i) * b(1, i) + b(2, i) * b(2, i);
  } else {
    fastSymmetricEigen(normalMatrixOf(f), w, q);
  }
  bool regular;
  return svdFromEigenOf<ScalarMath>(f, w, q, u, s, v, regular);
}

// F = U diag(s) V^T: the closed-form eigen-solve when its factors reproduce F to 1e-11, the
// Jacobi one otherwise.
GALSCULPT_HD void rotationVariantSvd(const M3& f, M3& u, double s[3], M3& v) {
  if (!(svdFromNormalMatrix(f, false, u, s, v) < 1e-11)) svdFromNormalMatrix(f, true, u, s, v);
}

// In-place Cholesky A = L L^T of an n x n column-major block (lower triangle); false when not
// positive definite.
GALSCULPT_HD bool cholesky(int n, double* a) {
  for (int j = 0; j < n; ++j) {
    double d = a[j + n * j];
    for (int k = 0; k < j; ++k) d -= a[j + n * k] * a[j + n * k];
    if (!(d > 0.0)) return false;
    d = sqrt(d);
    a[j + n * j] = d;
    for (int i = j + 1; i < n; ++i) {
      double s = a[i + n * j];
      for (int k = 0; k < j; ++k) s -= a[i + n * k] * a[j + n * k];
      a[i + n * j] = s / d;
    }
  }
  return true;
}

// Solves L L^T x = b in place (b becomes x).
GALSCULPT_HD void choleskySolve(int n, const double* l, double* b) {
  for (int i = 0; i < n; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= l[i + n * k] * b[k];
    b[i] = s / l[i + n * i];
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = b[i];
    for (int k = i + 1; k < n; ++k) s -= l[k + n * i] * b[k];
    b[i] = s / l[i + n * i];
  }
}

}  // namespace galsculpt::kernels
