// Linear corotational elasticity in the singular values s of F:
//   Psi = mu sum (s_i - 1)^2 + lambda/2 (sum s_i - 3)^2.
// No closed form from F alone (it needs the rotation): every evaluation goes through the SVD.
#pragma once

#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

struct Corotational {
  static constexpr bool kDirect = false;

  template <typename T, typename Math>
  GALSCULPT_HD static void singularValues(const Lame& lame, const T s[3], T& energy, T gradient[3],
                                          T hessian[3][3]) {
    const double mu = lame.mu, lambda = lame.lambda;
    const T trace = s[0] + s[1] + s[2] - 3.0;
    energy = 0.5 * lambda * trace * trace;
    for (int i = 0; i < 3; ++i) {
      energy += mu * (s[i] - 1.0) * (s[i] - 1.0);
      gradient[i] = 2.0 * mu * (s[i] - 1.0) + lambda * trace;
      for (int j = 0; j < 3; ++j) hessian[i][j] = Math::all(lambda + (i == j ? 2.0 * mu : 0.0));
    }
  }
};

}  // namespace galsculpt::kernels
