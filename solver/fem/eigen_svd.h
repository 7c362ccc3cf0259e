// The 3x3 symmetric eigen-solves and the SVD of a deformation gradient over a number type: one
// source for the scalar kernels (double, on the CPU and the GPU: kernel_math.h's functions) and
// the SIMD lanes (element_lanes_body.h: four elements at once), so that each lane rounds exactly
// as the scalar kernel does.
//
// The code is written for lanes: `Math` gives the number type's operations and its Mask (what a
// comparison gives: bool for double), a branch is a selection, and a loop that stops early runs
// until every lane has stopped, each lane keeping its values from where it stopped. A selection
// between two computed values is exact, so double gets the bits of the branches it replaces.
// What differs by type is in Math alone: ScalarMath below for double, LaneMath in the lanes.
// `Mat` is a 3x3 column-major matrix of the number type (a[9], m(r, c)).
#pragma once

#include <cmath>

#include "solver/fem/host_device.h"

namespace galsculpt::kernels {

// The number type double's operations (the material models' and the eigen-solves').
struct ScalarMath {
  using Mask = bool;
  GALSCULPT_HD static double all(double x) { return x; }
  GALSCULPT_HD static double log(double x) { return ::log(x); }
  GALSCULPT_HD static double sqrt(double x) { return ::sqrt(x); }
  GALSCULPT_HD static double abs(double x) { return fabs(x); }
  GALSCULPT_HD static double max(double x, double y) { return fmax(x, y); }
  // acos of x clamped to [-1, 1] (a NaN clamps to -1, as fmax takes the number).
  GALSCULPT_HD static double clampedAcos(double x) { return ::acos(::fmin(1.0, ::fmax(-1.0, x))); }
  GALSCULPT_HD static double cos(double x) { return ::cos(x); }
  GALSCULPT_HD static double select(bool m, double x, double y) { return m ? x : y; }
  GALSCULPT_HD static bool any(bool m) { return m; }
  GALSCULPT_HD static bool invert(bool m) { return !m; }
};

template <typename Math, typename Mat>
GALSCULPT_HD auto maxAbsOf(const Mat& m) {
  auto s = Math::all(0.0);
  for (const auto& v : m.a) s = Math::max(s, Math::abs(v));
  return s;
}

template <typename Mat>
GALSCULPT_HD auto determinantOf(const Mat& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(2, 1) * m(1, 2)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(2, 0) * m(1, 2)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(2, 0) * m(1, 1));
}

template <typename T>
GALSCULPT_HD void crossOf(const T x[3], const T y[3], T out[3]) {
  out[0] = x[1] * y[2] - x[2] * y[1];
  out[1] = x[2] * y[0] - x[0] * y[2];
  out[2] = x[0] * y[1] - x[1] * y[0];
}

template <typename Math, typename Mat>
GALSCULPT_HD void setIdentity(Mat& q) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) q(r, c) = Math::all(r == c ? 1.0 : 0.0);
}

// u diag(d) v^T.
template <typename Mat, typename T>
GALSCULPT_HD Mat scaledProductOf(const Mat& u, const T d[3], const Mat& v) {
  Mat m;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      m(r, c) = u(r, 0) * d[0] * v(c, 0) + u(r, 1) * d[1] * v(c, 1) + u(r, 2) * d[2] * v(c, 2);
  return m;
}

// F^T F.
template <typename Mat>
GALSCULPT_HD Mat normalMatrixOf(const Mat& f) {
  Mat m;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m(r, c) = f(0, r) * f(0, c) + f(1, r) * f(1, c) + f(2, r) * f(2, c);
  return m;
}

// Symmetric eigen-solve by cyclic Jacobi in the lanes of `active`: a = q diag(w) q^T, q a
// rotation. Accurate for repeated eigenvalues (where closed forms lose orthogonality).
template <typename Math, typename Mat, typename T>
GALSCULPT_HD void jacobiEigenOf(const Mat& input, T w[3], Mat& q, typename Math::Mask active) {
  using Mask = typename Math::Mask;
  T a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = 0.5 * (input(r, c) + input(c, r));
  setIdentity<Math>(q);
  Mask running = active;
  for (int sweep = 0; sweep < 32; ++sweep) {
    const T off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const T diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    running &= (off > 1e-34 * diag) & (off > 1e-300);
    if (!Math::any(running)) break;
    for (int pair = 0; pair < 3; ++pair) {
      const int p = pair == 2 ? 1 : 0, k = pair == 0 ? 1 : 2;
      const T apk = a[p][k];
      const Mask rotate = running & (apk != 0.0);
      const T theta = (a[k][k] - a[p][p]) / (2.0 * Math::select(rotate, apk, Math::all(1.0)));
      const T tNear = Math::select(theta >= 0.0, Math::all(1.0), Math::all(-1.0)) /
                      (Math::abs(theta) + Math::sqrt(theta * theta + 1.0));
      const T t = Math::select(Math::abs(theta) > 1e150, 0.5 / theta, tNear);
      const T c = 1.0 / Math::sqrt(t * t + 1.0), s = t * c;
      for (int i = 0; i < 3; ++i) {  // A <- A J
        const T aip = a[i][p], aik = a[i][k];
        a[i][p] = Math::select(rotate, c * aip - s * aik, aip);
        a[i][k] = Math::select(rotate, s * aip + c * aik, aik);
      }
      for (int i = 0; i < 3; ++i) {  // A <- J^T A
        const T api = a[p][i], aki = a[k][i];
        a[p][i] = Math::select(rotate, c * api - s * aki, api);
        a[k][i] = Math::select(rotate, s * api + c * aki, aki);
      }
      for (int i = 0; i < 3; ++i) {  // Q <- Q J
        const T qip = q(i, p), qik = q(i, k);
        q(i, p) = Math::select(rotate, c * qip - s * qik, qip);
        q(i, k) = Math::select(rotate, s * qip + c * qik, qik);
      }
    }
  }
  for (int i = 0; i < 3; ++i) w[i] = a[i][i];
}

// The eigenvalues of a symmetric matrix a in closed form (Cardano's trigonometric roots):
// shift + scale t_i, t the roots of b = (a - shift I) / scale (trace 0, largest entry 1), t[0]
// the smallest and t[2] the largest. scale 0: a = shift I (t zero).
template <typename T, typename Mat>
struct CardanoRootsOf {
  Mat b;
  T shift, scale, t[3];
};

// The lanes whose scale is a number (false: a NaN).
template <typename Math, typename Mat, typename T>
GALSCULPT_HD typename Math::Mask cardanoRootsOf(const Mat& a, CardanoRootsOf<T, Mat>& r) {
  r.shift = (a(0, 0) + a(1, 1) + a(2, 2)) / 3.0;
  r.b = a;
  Mat& b = r.b;
  for (int i = 0; i < 3; ++i) b(i, i) -= r.shift;
  r.scale = maxAbsOf<Math>(b);
  const auto positive = r.scale > 0.0;
  const T divisor = Math::select(positive, r.scale, Math::all(1.0));
  for (auto& x : b.a) x /= divisor;
  // Roots of det(b - t I) = 0 with tr b = 0: t = 2 sqrt(p/3) cos(phi - 2 pi k / 3).
  const T off = b(0, 1) * b(0, 1) + b(0, 2) * b(0, 2) + b(1, 2) * b(1, 2);
  const T p = (b(0, 0) * b(0, 0) + b(1, 1) * b(1, 1) + b(2, 2) * b(2, 2) + 2.0 * off) / 6.0;
  const T sq = Math::sqrt(p);
  const T half = determinantOf(b) / (2.0 * p * sq);
  const T phi = Math::clampedAcos(half) / 3.0;
  const T zero = Math::all(0.0);
  r.t[2] = Math::select(positive, 2.0 * sq * Math::cos(phi), zero);  // largest
  r.t[0] = Math::select(positive, 2.0 * sq * Math::cos(phi + 2.0943951023931954923), zero);
  r.t[1] = Math::select(positive, -r.t[0] - r.t[2], zero);
  return positive | (r.scale == 0.0);
}

// The eigen-solve in closed form (Cardano's roots, eigenvectors from cross products of the rows
// of A - w I), several times cheaper than Jacobi; the lanes where it is accurate (not nearly
// repeated eigenvalues), checked by the reconstruction |q diag(w) q^T - a|.
template <typename Math, typename Mat, typename T>
GALSCULPT_HD typename Math::Mask closedFormEigenOf(const Mat& a, T w[3], Mat& q) {
  using Mask = typename Math::Mask;
  CardanoRootsOf<T, Mat> roots;
  cardanoRootsOf<Math>(a, roots);
  const T shift = roots.shift, scale = roots.scale;
  const Mask multipleOfIdentity = scale == 0.0;
  Mask ok = scale > 0.0;
  const Mat& b = roots.b;
  const T* t = roots.t;
  const T zero = Math::all(0.0);
  // The most isolated eigenvalue first (the largest or the smallest): its kernel is well
  // conditioned; vk spans it, the largest of the cross products of the rows of b - t_k I.
  const Mask kIsLargest = (t[2] - t[1]) > (t[1] - t[0]);
  const T value = Math::select(kIsLargest, t[2], t[0]);
  T vk[3] = {zero, zero, zero};
  {
    const T r[3][3] = {{b(0, 0) - value, b(0, 1), b(0, 2)},
                       {b(1, 0), b(1, 1) - value, b(1, 2)},
                       {b(2, 0), b(2, 1), b(2, 2) - value}};
    T best = zero;
    for (int i = 0; i < 3; ++i) {
      T c[3];
      crossOf(r[i], r[(i + 1) % 3], c);
      const T n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      const Mask better = n > best;
      best = Math::select(better, n, best);
      for (int j = 0; j < 3; ++j) vk[j] = Math::select(better, c[j], vk[j]);
    }
    ok &= best > 0.0;
    const T inv = 1.0 / Math::sqrt(Math::select(ok, best, Math::all(1.0)));
    for (int j = 0; j < 3; ++j) vk[j] *= inv;
  }
  // The middle eigenvector is orthogonal to vk and to every row of b - t1 I.
  T v1[3] = {zero, zero, zero};
  {
    T best = zero;
    for (int i = 0; i < 3; ++i) {
      const T r[3] = {b(i, 0) - (i == 0 ? t[1] : zero), b(i, 1) - (i == 1 ? t[1] : zero),
                      b(i, 2) - (i == 2 ? t[1] : zero)};
      T c[3];
      crossOf(vk, r, c);
      const T n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      const Mask better = n > best;
      best = Math::select(better, n, best);
      for (int j = 0; j < 3; ++j) v1[j] = Math::select(better, c[j], v1[j]);
    }
    ok &= best > 1e-20;
    const T norm = Math::sqrt(Math::select(ok, best, Math::all(1.0)));
    for (T& x : v1) x /= norm;
  }
  T other[3];
  crossOf(vk, v1, other);
  for (int r = 0; r < 3; ++r) {  // vk in column 2 or 0, the remaining extreme in the other
    q(r, 0) = Math::select(kIsLargest, other[r], vk[r]);
    q(r, 1) = v1[r];
    q(r, 2) = Math::select(kIsLargest, vk[r], other[r]);
  }
  const Mask flip = determinantOf(q) < 0.0;  // a rotation: the remaining extreme turned
  for (int r = 0; r < 3; ++r) {
    q(r, 0) = Math::select(flip & kIsLargest, -q(r, 0), q(r, 0));
    q(r, 2) = Math::select(flip & Math::invert(kIsLargest), -q(r, 2), q(r, 2));
  }
  for (int i = 0; i < 3; ++i) w[i] = t[i] * scale + shift;
  // Accept only an accurate reconstruction.
  const T tolerance = 1e-11 * Math::max(maxAbsOf<Math>(a), Math::all(1e-300));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const T value =
          q(r, 0) * w[0] * q(c, 0) + q(r, 1) * w[1] * q(c, 1) + q(r, 2) * w[2] * q(c, 2);
      ok &= Math::abs(value - a(r, c)) <= tolerance;
    }
  // A multiple of the identity: w = shift, q = I.
  for (int i = 0; i < 3; ++i) w[i] = Math::select(multipleOfIdentity, shift, w[i]);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      q(r, c) = Math::select(multipleOfIdentity, Math::all(r == c ? 1.0 : 0.0), q(r, c));
  return ok | multipleOfIdentity;
}

// The closed form where accurate, Jacobi in the other lanes of `inUse`.
template <typename Math, typename Mat, typename T>
GALSCULPT_HD void fastEigenOf(const Mat& a, T w[3], Mat& q, typename Math::Mask inUse) {
  const auto jacobi = Math::invert(closedFormEigenOf<Math>(a, w, q)) & inUse;
  if (!Math::any(jacobi)) return;
  T wj[3];
  Mat qj;
  jacobiEigenOf<Math>(a, wj, qj, jacobi);
  for (int i = 0; i < 3; ++i) w[i] = Math::select(jacobi, wj[i], w[i]);
  for (int i = 0; i < 9; ++i) q.a[i] = Math::select(jacobi, qj.a[i], q.a[i]);
}

// F = U diag(s) V^T (the rotation-variant SVD of Irving et al.: U, V rotations, s sorted by
// magnitude of the first two, s[2] < 0 when F is inverted) from the eigensystem (w, q) of
// F^T F. Returns the largest part of F V that the factors drop over |F| (zero in exact
// arithmetic); `regular`: the lanes whose first two columns of F V are not negligible (a rank
// one or zero F takes any unit vectors there, its singular values zero).
template <typename Math, typename Mat, typename T>
GALSCULPT_HD T svdFromEigenOf(const Mat& f, T w[3], Mat& q, Mat& u, T s[3], Mat& v,
                              typename Math::Mask& regular) {
  using Mask = typename Math::Mask;
  // Descending eigenvalues of F^T F: a selection sort as compare-exchanges.
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto& pair : pairs) {
    const int i = pair[0], j = pair[1];
    const Mask swap = w[j] > w[i];
    const T wi = w[i];
    w[i] = Math::select(swap, w[j], wi);
    w[j] = Math::select(swap, wi, w[j]);
    for (int r = 0; r < 3; ++r) {
      const T qi = q(r, i);
      q(r, i) = Math::select(swap, q(r, j), qi);
      q(r, j) = Math::select(swap, qi, q(r, j));
    }
  }
  v = q;
  const Mask reflect = determinantOf(v) < 0.0;
  for (int r = 0; r < 3; ++r) v(r, 2) = Math::select(reflect, -v(r, 2), v(r, 2));
  Mat b;  // columns s_i u_i
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) b(r, c) = f(r, 0) * v(0, c) + f(r, 1) * v(1, c) + f(r, 2) * v(2, c);
  const T scale = Math::max(maxAbsOf<Math>(f), Math::all(1e-300));
  const T zero = Math::all(0.0), one = Math::all(1.0);
  const T n0 = Math::sqrt(b(0, 0) * b(0, 0) + b(1, 0) * b(1, 0) + b(2, 0) * b(2, 0));
  const Mask n0Regular = n0 > 1e-14 * scale;
  const T n0Safe = Math::select(n0Regular, n0, one);
  T u0[3];
  for (int r = 0; r < 3; ++r)
    u0[r] = Math::select(n0Regular, b(r, 0) / n0Safe, r == 0 ? one : zero);
  const T proj = u0[0] * b(0, 1) + u0[1] * b(1, 1) + u0[2] * b(2, 1);
  T u1[3] = {b(0, 1) - proj * u0[0], b(1, 1) - proj * u0[1], b(2, 1) - proj * u0[2]};
  const T n1 = Math::sqrt(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
  const Mask n1Regular = n1 > 1e-14 * scale;
  const T n1Safe = Math::select(n1Regular, n1, one);
  for (int r = 0; r < 3; ++r) u1[r] /= n1Safe;
  if (Math::any(Math::invert(n1Regular))) {
    // Rank one or zero: the axis least along u0, made orthogonal to it.
    const T a0 = Math::abs(u0[0]), a1 = Math::abs(u0[1]), a2 = Math::abs(u0[2]);
    const Mask axis0 = (a0 <= a1) & (a0 <= a2);
    const Mask axis1 = Math::invert(axis0) & (a1 <= a2);
    const Mask axis2 = Math::invert(axis0) & Math::invert(axis1);
    const T d = Math::select(axis0, u0[0], Math::select(axis1, u0[1], u0[2]));
    const T e[3] = {Math::select(axis0, one, zero), Math::select(axis1, one, zero),
                    Math::select(axis2, one, zero)};
    T across[3];
    for (int r = 0; r < 3; ++r) across[r] = e[r] - d * u0[r];
    const T nAcross =
        Math::sqrt(across[0] * across[0] + across[1] * across[1] + across[2] * across[2]);
    for (int r = 0; r < 3; ++r) u1[r] = Math::select(n1Regular, u1[r], across[r] / nAcross);
  }
  regular = n0Regular & n1Regular;
  T u2[3];
  crossOf(u0, u1, u2);
  for (int r = 0; r < 3; ++r) {
    u(r, 0) = u0[r];
    u(r, 1) = u1[r];
    u(r, 2) = u2[r];
  }
  for (int i = 0; i < 3; ++i) s[i] = u(0, i) * b(0, i) + u(1, i) * b(1, i) + u(2, i) * b(2, i);
  T dropped = zero;  // U^T F V off its diagonal
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j)
        dropped = Math::max(dropped,
                            Math::abs(u(0, i) * b(0, j) + u(1, i) * b(1, j) + u(2, i) * b(2, j)));
  return dropped / scale;
}

}  // namespace galsculpt::kernels
