#include "isotropic_material.h"

#include <cmath>
#include <stdexcept>

namespace galsculpt {

MaterialModel materialModelFromName(const std::string& name) {
  if (name == "corotational") return MaterialModel::Corotational;
  if (name == "stvk") return MaterialModel::StVK;
  if (name == "stable_neo_hookean") return MaterialModel::StableNeoHookean;
  throw std::invalid_argument("unknown material model '" + name + "'");
}

Lame lameFromYoungPoisson(double e, double nu) {
  return {e / (2.0 * (1.0 + nu)), e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))};
}

SingularValueEnergy evaluateSingularValueEnergy(MaterialModel model, const Lame& lame,
                                                const Eigen::Vector3d& s) {
  SingularValueEnergy out;
  const double mu = lame.mu, lambda = lame.lambda;
  switch (model) {
    case MaterialModel::Corotational: {
      // mu |F - R|^2 + lambda/2 tr(S - I)^2 with S = R^T F: in singular values,
      // mu sum (s_i - 1)^2 + lambda/2 (sum s_i - 3)^2.
      const double trace = s.sum() - 3.0;
      out.energy = mu * (s.array() - 1.0).square().sum() + 0.5 * lambda * trace * trace;
      out.gradient =
          2.0 * mu * (s.array() - 1.0).matrix() + Eigen::Vector3d::Constant(lambda * trace);
      out.hessian = 2.0 * mu * Eigen::Matrix3d::Identity() + Eigen::Matrix3d::Constant(lambda);
      break;
    }
    case MaterialModel::StVK: {
      // mu |E|^2 + lambda/2 tr(E)^2 with E = (F^T F - I)/2, principal strains e_i = (s_i^2 - 1)/2.
      const Eigen::Array3d e = 0.5 * (s.array().square() - 1.0);
      const double trace = e.sum();
      out.energy = mu * e.square().sum() + 0.5 * lambda * trace * trace;
      const Eigen::Array3d dPsiDe = 2.0 * mu * e + lambda * trace;
      out.gradient = (dPsiDe * s.array()).matrix();
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          out.hessian(i, j) =
              s[i] * s[j] * (lambda + (i == j ? 2.0 * mu : 0.0)) + (i == j ? dPsiDe[i] : 0.0);
        }
      }
      break;
    }
    case MaterialModel::StableNeoHookean: {
      // Smith, de Goes, Kim 2018, eq. 14, with the Lame parameters re-fitted so that small
      // strains match linear elasticity (their section 3.4) and alpha making the rest state
      // stress-free with the log term.
      const double muS = 4.0 / 3.0 * mu;
      const double lambdaS = lambda + 5.0 / 6.0 * mu;
      const double alpha = 1.0 + 0.75 * muS / lambdaS;
      const double ic = s.squaredNorm();
      const double j = s.prod();
      const Eigen::Vector3d cofactor(s[1] * s[2], s[0] * s[2], s[0] * s[1]);  // dJ/ds_i
      // Shifted by its rest value so that the undeformed state stores no energy.
      const double restEnergy =
          0.5 * lambdaS * (1.0 - alpha) * (1.0 - alpha) - 0.5 * muS * std::log(4.0);
      out.energy = 0.5 * muS * (ic - 3.0) + 0.5 * lambdaS * (j - alpha) * (j - alpha) -
                   0.5 * muS * std::log(ic + 1.0) - restEnergy;
      const double shear = muS * (1.0 - 1.0 / (ic + 1.0));
      out.gradient = shear * s + lambdaS * (j - alpha) * cofactor;
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          double h = 2.0 * muS * s[a] * s[b] / ((ic + 1.0) * (ic + 1.0)) +
                     lambdaS * cofactor[a] * cofactor[b];
          if (a == b) {
            h += shear;
          } else {
            h += lambdaS * (j - alpha) * s[3 - a - b];  // d(s_b s_c)/ds_a for the third index
          }
          out.hessian(a, b) = h;
        }
      }
      break;
    }
  }
  return out;
}

}  // namespace galsculpt
