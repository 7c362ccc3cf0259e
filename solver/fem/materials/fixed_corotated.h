// Fixed corotated elasticity (Stomakhin et al. 2012) in the singular values s of F:
//   Psi = mu sum (s_i - 1)^2 + lambda/2 (J - 1)^2, J = s_0 s_1 s_2.
// The volume term in J instead of corotational's trace keeps it well posed under strong
// compression and through inversion. Evaluated through the SVD (no closed form from F alone).
#pragma once

#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

struct FixedCorotated {
  static constexpr bool kDirect = false;

  template <typename T, typename Math>
  GALSCULPT_HD static void singularValues(const Lame& lame, const T s[3], T& energy, T gradient[3],
                                          T hessian[3][3]) {
    const double mu = lame.mu, lambda = lame.lambda;
    const T j = s[0] * s[1] * s[2];
    const T cof[3] = {s[1] * s[2], s[0] * s[2], s[0] * s[1]};
    energy = 0.5 * lambda * (j - 1.0) * (j - 1.0);
    for (int i = 0; i < 3; ++i) {
      energy += mu * (s[i] - 1.0) * (s[i] - 1.0);
      gradient[i] = 2.0 * mu * (s[i] - 1.0) + lambda * (j - 1.0) * cof[i];
    }
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        hessian[a][b] = a == b ? 2.0 * mu + lambda * cof[a] * cof[a]
                               : lambda * cof[a] * cof[b] + lambda * (j - 1.0) * s[3 - a - b];
  }
};

}  // namespace galsculpt::kernels
