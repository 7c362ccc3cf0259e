// Stable neo-Hookean (Smith, de Goes, Kim 2018, eq. 14), its Lame parameters re-fitted to linear
// elasticity (their section 3.4) and shifted so that the rest state stores no energy:
//   Psi = mu'/2 (I_C - 3) + lambda'/2 (J - alpha)^2 - mu'/2 log(I_C + 1) - Psi_rest,
//   mu' = 4/3 mu, lambda' = lambda + 5/6 mu, alpha = 1 + 3/4 mu'/lambda'.
// Well posed under compression and through inversion.
#pragma once

#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

struct StableNeoHookean {
  static constexpr bool kDirect = true;

  // mu', lambda', alpha and the rest energy Psi_rest of the user's Lame parameters. A template on
  // the caller's math so that the SIMD lanes' instantiation stays in their own file.
  struct Refit {
    double muS, lambdaS, alpha, restEnergy;
  };
  template <typename Math = void>
  GALSCULPT_HD static Refit refit(const Lame& lame) {
    const double muS = 4.0 / 3.0 * lame.mu;
    const double lambdaS = lame.lambda + 5.0 / 6.0 * lame.mu;
    const double alpha = 1.0 + 0.75 * muS / lambdaS;
    return {muS, lambdaS, alpha,
            0.5 * lambdaS * (1.0 - alpha) * (1.0 - alpha) - 0.5 * muS * log(4.0)};
  }

  template <typename T, typename Math>
  GALSCULPT_HD static void singularValues(const Lame& lame, const T s[3], T& energy, T gradient[3],
                                          T hessian[3][3]) {
    const Refit r = refit<Math>(lame);
    const double muS = r.muS, lambdaS = r.lambdaS, alpha = r.alpha, restEnergy = r.restEnergy;
    const T ic = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
    const T j = s[0] * s[1] * s[2];
    const T cof[3] = {s[1] * s[2], s[0] * s[2], s[0] * s[1]};
    energy = 0.5 * muS * (ic - 3.0) + 0.5 * lambdaS * (j - alpha) * (j - alpha) -
             0.5 * muS * Math::log(ic + 1.0) - restEnergy;
    const T shear = muS * (1.0 - 1.0 / (ic + 1.0));
    for (int a = 0; a < 3; ++a) gradient[a] = shear * s[a] + lambdaS * (j - alpha) * cof[a];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        T h = 2.0 * muS * s[a] * s[b] / ((ic + 1.0) * (ic + 1.0)) + lambdaS * cof[a] * cof[b];
        h += a == b ? shear : lambdaS * (j - alpha) * s[3 - a - b];
        hessian[a][b] = h;
      }
    }
  }

  // Psi and P straight from F: P = mu' (1 - 1/(I_C + 1)) F + lambda' (J - alpha) cof(F).
  GALSCULPT_HD static M3 direct(const Lame& lame, const M3& f, double& psi) {
    M3 p{};
    const Refit r = refit<>(lame);
    const double muS = r.muS, lambdaS = r.lambdaS, alpha = r.alpha, restEnergy = r.restEnergy;
    const double ic = squaredNorm(f);
    const double j = determinant(f);
    const M3 cof = cofactor(f);
    psi = 0.5 * muS * (ic - 3.0) + 0.5 * lambdaS * (j - alpha) * (j - alpha) -
          0.5 * muS * log(ic + 1.0) - restEnergy;
    const double shear = muS * (1.0 - 1.0 / (ic + 1.0));
    for (int i = 0; i < 9; ++i) p.a[i] = shear * f.a[i] + lambdaS * (j - alpha) * cof.a[i];
    return p;
  }
};

}  // namespace galsculpt::kernels
