// St. Venant-Kirchhoff: Psi = mu |E|^2 + lambda/2 tr(E)^2 with E = (F^T F - I)/2. It softens
// and loses stability in strong compression (a body can invert under load).
#pragma once

#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

struct StVK {
  static constexpr bool kDirect = true;

  // In the principal strains e_i = (s_i^2 - 1)/2.
  template <typename T, typename Math>
  GALSCULPT_HD static void singularValues(const Lame& lame, const T s[3], T& energy, T gradient[3],
                                          T hessian[3][3]) {
    const double mu = lame.mu, lambda = lame.lambda;
    T e[3], dPsiDe[3];
    for (int i = 0; i < 3; ++i) e[i] = 0.5 * (s[i] * s[i] - 1.0);
    const T trace = e[0] + e[1] + e[2];
    energy = 0.5 * lambda * trace * trace;
    for (int i = 0; i < 3; ++i) {
      energy += mu * e[i] * e[i];
      dPsiDe[i] = 2.0 * mu * e[i] + lambda * trace;
      gradient[i] = dPsiDe[i] * s[i];
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        hessian[i][j] = s[i] * s[j] * (lambda + (i == j ? 2.0 * mu : 0.0)) +
                        (i == j ? dPsiDe[i] : Math::all(0.0));
  }

  // Psi and P = F S straight from F.
  GALSCULPT_HD static M3 direct(const Lame& lame, const M3& f, double& psi) {
    M3 e = multiply(transpose(f), f);
    for (int i = 0; i < 9; ++i) e.a[i] *= 0.5;
    for (int i = 0; i < 3; ++i) e(i, i) -= 0.5;
    const double trace = e(0, 0) + e(1, 1) + e(2, 2);
    psi = lame.mu * squaredNorm(e) + 0.5 * lame.lambda * trace * trace;
    M3 s = e;
    for (int i = 0; i < 9; ++i) s.a[i] *= 2.0 * lame.mu;
    for (int i = 0; i < 3; ++i) s(i, i) += lame.lambda * trace;
    return multiply(f, s);
  }
};

}  // namespace galsculpt::kernels
