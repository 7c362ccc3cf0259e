// An intact element's kinematics and the eigensystem of its dP/dF over a number type, in the
// manner of eigen_svd.h: one source for the scalar kernel (element_kernels.h, material_kernels.h:
// double on the CPU and the GPU) and the SIMD lanes (element_lanes_body.h), so that each lane
// rounds exactly as the scalar kernel does. `Math` gives the number type's operations,
// `Mat` is a 3x3 column-major matrix of it.
#pragma once

#include "solver/fem/eigen_svd.h"
#include "solver/fem/host_device.h"

namespace galsculpt::kernels {

// Psi and its derivatives in the singular values s of F (per unit rest volume).
template <typename T, typename Mat>
struct SingularValueEnergyOf {
  T energy{};  // J/m^3
  T gradient[3]{};
  Mat hessian{};  // d2 Psi / ds_i ds_j
};

// F = Ds Dm^-1, Ds = [x1 - x0, x2 - x0, x3 - x0].
template <typename Mat, typename T>
GALSCULPT_HD Mat deformationGradientOf(const Mat& dmInverse, const T x[12]) {
  Mat ds, f;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) ds(r, c) = x[3 * (c + 1) + r] - x[r];
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      f(r, c) =
          ds(r, 0) * dmInverse(0, c) + ds(r, 1) * dmInverse(1, c) + ds(r, 2) * dmInverse(2, c);
  return f;
}

// Shape-function gradients: F = sum_a x_a c_a^T, c_0 = -(c_1 + c_2 + c_3); c[a][j].
template <typename Math, typename Mat, typename T>
GALSCULPT_HD void shapeGradientsOf(const Mat& dmInverse, T c[4][3]) {
  for (int j = 0; j < 3; ++j) {
    c[0][j] = Math::all(0.0);
    for (int a = 1; a < 4; ++a) {
      c[a][j] = dmInverse.a[(a - 1) + 3 * j];
      c[0][j] -= c[a][j];
    }
  }
}

// The force on the corners of stress P: volume P c_a.
template <typename Mat, typename T>
GALSCULPT_HD void elementForceOf(const T& volume, const Mat& p, const T c[4][3], T gradient[12]) {
  for (int a = 0; a < 4; ++a)
    for (int r = 0; r < 3; ++r)
      gradient[3 * a + r] = volume * (p(r, 0) * c[a][0] + p(r, 1) * c[a][1] + p(r, 2) * c[a][2]);
}

// dF/dx^T vec Q = [Q c_0; Q c_1; Q c_2; Q c_3]: a mode of dP/dF on the corners.
template <typename Mat, typename T>
GALSCULPT_HD void modeVectorOf(const Mat& q, const T c[4][3], T w[12]) {
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      w[3 * a + i] = q(i, 0) * c[a][0] + q(i, 1) * c[a][1] + q(i, 2) * c[a][2];
}

// The analytic eigensystem of dP/dF: calls visit(lambda, Q) for its 3 scaling modes (the
// eigenvectors of the singular-value Hessian), 3 twist and 3 flip modes; dP/dF is
// sum lambda vec(Q) vec(Q)^T, and projecting it to SPD is clamping each lambda at zero.
// `inUse`: the lanes whose eigen-solve matters (eigen_svd.h's fastEigenOf).
template <typename Math, typename Mat, typename T, typename Visit>
GALSCULPT_HD void forEachStressModeOf(const Mat& u, const T s[3], const Mat& v,
                                      const SingularValueEnergyOf<T, Mat>& e,
                                      typename Math::Mask inUse, Visit visit) {
  {
    T w[3];
    Mat q;
    fastEigenOf<Math>(e.hessian, w, q, inUse);
    for (int m = 0; m < 3; ++m) {
      const T d[3] = {q(0, m), q(1, m), q(2, m)};
      visit(w[m], scaledProductOf(u, d, v));
    }
  }
  const double invSqrt2 = 0.70710678118654752440;
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      // U T V^T with T the twist (flip) of the pair: (u_i v_j^T -+ u_j v_i^T) / sqrt 2.
      Mat twist, flip;
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
          const T a = u(r, i) * v(c, j) * invSqrt2, b = u(r, j) * v(c, i) * invSqrt2;
          twist(r, c) = a - b;
          flip(r, c) = a + b;
        }
      }
      const T gi = e.gradient[i], gj = e.gradient[j];
      // (gi -+ gj) / (si -+ sj), its limit where the denominator is about zero.
      const T sumDen = s[i] + s[j], diffDen = s[i] - s[j];
      visit(Math::select(Math::abs(sumDen) < 1e-8, e.hessian(i, i) + e.hessian(i, j),
                         (gi + gj) / sumDen),
            twist);
      visit(Math::select(Math::abs(diffDen) < 1e-8, e.hessian(i, i) - e.hessian(i, j),
                         (gi - gj) / diffDen),
            flip);
    }
  }
}

}  // namespace galsculpt::kernels
