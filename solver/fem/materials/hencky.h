// Hencky elasticity with von Mises flow in its energy (docs/physics.md, "Plasticity inside the
// solve"): in the principal Hencky strains e_i = l(s_i) (hencky_strain.h, the logarithm
// continued below a stretch of 0.1),
//   Psi = G(|dev e|) + kappa/2 (tr e)^2,   kappa = lambda + 2/3 mu,
// G the deviatoric energy with the step's plastic flow minimized out (deviatoricFlow): mu |dev e|^2
// inside the yield surface, and past it the energy whose gradient is the radial return's stress
// and whose Hessian is its consistent tangent. With `lame.yield` 0 it is plain Hencky
// elasticity. The flow is isochoric (it leaves tr e alone) and the yield stress is the
// element's own (its hardening), so the lanes evaluate this model one lane at a time.
#pragma once

#include <type_traits>

#include "solver/fem/hencky_strain.h"
#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

struct Hencky {
  static constexpr bool kDirect = false;
  static constexpr bool kLaneByLane = true;

  template <typename T, typename Math>
  GALSCULPT_HD static void singularValues(const Lame& lame, const T s[3], T& energy, T gradient[3],
                                          T hessian[3][3]) {
    static_assert(std::is_same_v<T, double>, "evaluated one element at a time");
    const double kappa = lame.lambda + 2.0 / 3.0 * lame.mu;
    const HenckyStrain h = henckyStrain(s);
    const DeviatoricFlow g = deviatoricFlow(lame.mu, lame.yield, lame.hardening, h.deviatorNorm);
    energy = g.energy + 0.5 * kappa * h.trace * h.trace;
    double n[3], dPsiDe[3];
    for (int i = 0; i < 3; ++i) {
      n[i] = h.deviatorNorm > 0.0 ? h.deviator[i] / h.deviatorNorm : 0.0;
      dPsiDe[i] = g.slopeOverS * h.deviator[i] + kappa * h.trace;
      gradient[i] = dPsiDe[i] * h.log[i].slope;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double projector = (i == j ? 1.0 : 0.0) - 1.0 / 3.0;
        const double d2PsiDe2 =
            g.curvature * n[i] * n[j] + g.slopeOverS * (projector - n[i] * n[j]) + kappa;
        hessian[i][j] = d2PsiDe2 * h.log[i].slope * h.log[j].slope +
                        (i == j ? dPsiDe[i] * h.log[i].curvature : 0.0);
      }
  }
};

}  // namespace galsculpt::kernels
