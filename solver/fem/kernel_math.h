// The small dense linear algebra of the element kernels in plain arrays, compiled for the CPU and
// the GPU: 3x3 matrices (column-major, as Eigen stores them), a 6x6 inverse, symmetric
// eigen-solves (cyclic Jacobi, robust for repeated and zero eigenvalues, and a closed form used
// where it is accurate) and the rotation-variant SVD of a deformation gradient.
//
// Header only, no Eigen, no exceptions, no allocation: every function is __host__ __device__
// under nvcc.
#pragma once

#include <cmath>

#if defined(__CUDACC__)
#define GALSCULPT_HD __host__ __device__ inline
#else
#define GALSCULPT_HD inline
#endif
// Unrolls the loop that follows where the compiler takes GCC's pragma (not under nvcc).
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#define GALSCULPT_UNROLL _Pragma("GCC unroll 8")
#else
#define GALSCULPT_UNROLL
#endif

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
  M3 m{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      m(r, c) = u(r, 0) * d[0] * v(c, 0) + u(r, 1) * d[1] * v(c, 1) + u(r, 2) * d[2] * v(c, 2);
  return m;
}

// Symmetric eigen-solve of a 3x3 matrix by cyclic Jacobi: a = q diag(w) q^T, q a rotation.
// Accurate for repeated eigenvalues (where closed forms lose orthogonality).
GALSCULPT_HD void symmetricEigen(const M3& input, double w[3], M3& q) {
  double a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = 0.5 * (input(r, c) + input(c, r));
  q = identity3();
  for (int sweep = 0; sweep < 32; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-34 * diag) || !(off > 1e-300)) break;
    for (int pair = 0; pair < 3; ++pair) {
      const int p = pair == 2 ? 1 : 0, k = pair == 0 ? 1 : 2;
      const double apk = a[p][k];
      if (apk == 0.0) continue;
      const double theta = (a[k][k] - a[p][p]) / (2.0 * apk);
      const double t = fabs(theta) > 1e150 ? 0.5 / theta
                                           : (theta >= 0.0 ? 1.0 : -1.0) /
                                                 (fabs(theta) + sqrt(theta * theta + 1.0));
      const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
      for (int i = 0; i < 3; ++i) {  // A <- A J
        const double aip = a[i][p], aik = a[i][k];
        a[i][p] = c * aip - s * aik;
        a[i][k] = s * aip + c * aik;
      }
      for (int i = 0; i < 3; ++i) {  // A <- J^T A
        const double api = a[p][i], aki = a[k][i];
        a[p][i] = c * api - s * aki;
        a[k][i] = s * api + c * aki;
      }
      for (int i = 0; i < 3; ++i) {  // Q <- Q J
        const double qip = q(i, p), qik = q(i, k);
        q(i, p) = c * qip - s * qik;
        q(i, k) = s * qip + c * qik;
      }
    }
  }
  for (int i = 0; i < 3; ++i) w[i] = a[i][i];
}

// The eigenvalues of a symmetric matrix a in closed form (Cardano's trigonometric roots):
// shift + scale t_i, t the roots of b = (a - shift I) / scale (trace 0, largest entry 1), t[0]
// the smallest and t[2] the largest. scale 0: a = shift I (t zero). False for a NaN entry.
struct CardanoRoots {
  M3 b;
  double shift, scale, t[3];
};

GALSCULPT_HD bool cardanoRoots(const M3& a, CardanoRoots& r) {
  r.shift = (a(0, 0) + a(1, 1) + a(2, 2)) / 3.0;
  r.b = a;
  M3& b = r.b;
  for (int i = 0; i < 3; ++i) b(i, i) -= r.shift;
  r.scale = maxAbs(b);
  if (!(r.scale > 0.0)) {
    r.t[0] = r.t[1] = r.t[2] = 0.0;
    return r.scale == 0.0;  // false: NaN
  }
  for (double& x : b.a) x /= r.scale;
  // Roots of det(b - t I) = 0 with tr b = 0: t = 2 sqrt(p/3) cos(phi - 2 pi k / 3).
  const double off = b(0, 1) * b(0, 1) + b(0, 2) * b(0, 2) + b(1, 2) * b(1, 2);
  const double p = (b(0, 0) * b(0, 0) + b(1, 1) * b(1, 1) + b(2, 2) * b(2, 2) + 2.0 * off) / 6.0;
  const double sq = sqrt(p);
  const double half = determinant(b) / (2.0 * p * sq);
  const double phi = acos(fmin(1.0, fmax(-1.0, half))) / 3.0;
  r.t[2] = 2.0 * sq * cos(phi);                          // largest
  r.t[0] = 2.0 * sq * cos(phi + 2.0943951023931954923);  // smallest (2 pi / 3)
  r.t[1] = -r.t[0] - r.t[2];
  return true;
}

// The same eigen-solve in closed form (Cardano's roots, eigenvectors from cross products of the
// rows of A - w I), several times cheaper than Jacobi; false where it is not accurate (nearly
// repeated eigenvalues), checked by the reconstruction |q diag(w) q^T - a| as the caller asks.
GALSCULPT_HD bool closedFormSymmetricEigen(const M3& a, double w[3], M3& q) {
  CardanoRoots roots;
  if (!cardanoRoots(a, roots)) return false;
  const double shift = roots.shift, scale = roots.scale;
  if (scale == 0.0) {
    w[0] = w[1] = w[2] = shift;
    q = identity3();
    return true;
  }
  const M3& b = roots.b;
  const double* t = roots.t;
  // The most isolated eigenvalue first: its kernel is well conditioned.
  const int k = (t[2] - t[1]) > (t[1] - t[0]) ? 2 : 0;
  auto kernelOf = [&](double value, double out[3]) {
    const double r[3][3] = {{b(0, 0) - value, b(0, 1), b(0, 2)},
                            {b(1, 0), b(1, 1) - value, b(1, 2)},
                            {b(2, 0), b(2, 1), b(2, 2) - value}};
    double best = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double* x = r[i];
      const double* y = r[(i + 1) % 3];
      const double c[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                           x[0] * y[1] - x[1] * y[0]};
      const double n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      if (n > best) {
        best = n;
        for (int j = 0; j < 3; ++j) out[j] = c[j];
      }
    }
    if (!(best > 0.0)) return false;
    const double inv = 1.0 / sqrt(best);
    for (int j = 0; j < 3; ++j) out[j] *= inv;
    return true;
  };
  double vk[3], v1[3];
  if (!kernelOf(t[k], vk)) return false;
  // The middle eigenvector is orthogonal to vk and to every row of b - t1 I.
  double best = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double r[3] = {b(i, 0) - (i == 0 ? t[1] : 0.0), b(i, 1) - (i == 1 ? t[1] : 0.0),
                         b(i, 2) - (i == 2 ? t[1] : 0.0)};
    const double c[3] = {vk[1] * r[2] - vk[2] * r[1], vk[2] * r[0] - vk[0] * r[2],
                         vk[0] * r[1] - vk[1] * r[0]};
    const double n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    if (n > best) {
      best = n;
      for (int j = 0; j < 3; ++j) v1[j] = c[j];
    }
  }
  if (!(best > 1e-20)) return false;
  for (double& x : v1) x /= sqrt(best);
  const double other[3] = {vk[1] * v1[2] - vk[2] * v1[1], vk[2] * v1[0] - vk[0] * v1[2],
                           vk[0] * v1[1] - vk[1] * v1[0]};
  const int o = 2 - k;  // the remaining extreme eigenvalue
  for (int r = 0; r < 3; ++r) {
    q(r, k) = vk[r];
    q(r, 1) = v1[r];
    q(r, o) = other[r];
  }
  if (determinant(q) < 0.0)
    for (int r = 0; r < 3; ++r) q(r, o) = -q(r, o);
  for (int i = 0; i < 3; ++i) w[i] = t[i] * scale + shift;
  // Accept only an accurate reconstruction.
  const double tolerance = 1e-11 * fmax(maxAbs(a), 1e-300);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const double value =
          q(r, 0) * w[0] * q(c, 0) + q(r, 1) * w[1] * q(c, 1) + q(r, 2) * w[2] * q(c, 2);
      if (!(fabs(value - a(r, c)) <= tolerance)) return false;
    }
  return true;
}

// Closed form where accurate, Jacobi otherwise.
GALSCULPT_HD void fastSymmetricEigen(const M3& a, double w[3], M3& q) {
  if (!closedFormSymmetricEigen(a, w, q)) symmetricEigen(a, w, q);
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
    fastSymmetricEigen(multiply(transpose(f), f), w, q);
  }
  // Descending eigenvalues of F^T F.
  int order[3] = {0, 1, 2};
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (w[order[j]] > w[order[i]]) {
        const int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) v(r, c) = q(r, order[c]);
  if (determinant(v) < 0.0)
    for (int r = 0; r < 3; ++r) v(r, 2) = -v(r, 2);
  const M3 b = multiply(f, v);  // columns s_i u_i
  const double scale = fmax(maxAbs(f), 1e-300);
  double n0 = sqrt(b(0, 0) * b(0, 0) + b(1, 0) * b(1, 0) + b(2, 0) * b(2, 0));
  double u0[3] = {1.0, 0.0, 0.0};
  if (n0 > 1e-14 * scale)
    for (int r = 0; r < 3; ++r) u0[r] = b(r, 0) / n0;
  const double proj = u0[0] * b(0, 1) + u0[1] * b(1, 1) + u0[2] * b(2, 1);
  double u1[3] = {b(0, 1) - proj * u0[0], b(1, 1) - proj * u0[1], b(2, 1) - proj * u0[2]};
  const double n1 = sqrt(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
  if (n1 > 1e-14 * scale) {
    for (double& x : u1) x /= n1;
  } else {
    // Rank one or zero: any unit vector orthogonal to u0 (its singular value is zero).
    const int axis = fabs(u0[0]) <= fabs(u0[1]) && fabs(u0[0]) <= fabs(u0[2])
                         ? 0
                         : (fabs(u0[1]) <= fabs(u0[2]) ? 1 : 2);
    double e[3] = {0.0, 0.0, 0.0};
    e[axis] = 1.0;
    const double d = u0[axis];
    for (int r = 0; r < 3; ++r) u1[r] = e[r] - d * u0[r];
    const double n = sqrt(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
    for (double& x : u1) x /= n;
  }
  const double u2[3] = {u0[1] * u1[2] - u0[2] * u1[1], u0[2] * u1[0] - u0[0] * u1[2],
                        u0[0] * u1[1] - u0[1] * u1[0]};
  for (int r = 0; r < 3; ++r) {
    u(r, 0) = u0[r];
    u(r, 1) = u1[r];
    u(r, 2) = u2[r];
  }
  for (int i = 0; i < 3; ++i) s[i] = u(0, i) * b(0, i) + u(1, i) * b(1, i) + u(2, i) * b(2, i);
  double dropped = 0.0;  // U^T F V off its diagonal
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j)
        dropped = fmax(dropped, fabs(u(0, i) * b(0, j) + u(1, i) * b(1, j) + u(2, i) * b(2, j)));
  return dropped / scale;
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
