#include "solver/fem/isotropic_material.h"

#include <cmath>
#include <stdexcept>

#include "solver/fem/material_kernels.h"

namespace galsculpt {

Lame lameFromYoungPoisson(double e, double nu) {
  return {e / (2.0 * (1.0 + nu)), e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))};
}

double youngsModulus(const Lame& l) {
  return l.mu * (3.0 * l.lambda + 2.0 * l.mu) / (l.lambda + l.mu);
}

SingularValueEnergy evaluateSingularValueEnergy(MaterialModel model, const Lame& lame,
                                                const Eigen::Vector3d& s) {
  const kernels::SingularValueEnergy k = kernels::singularValueEnergy(model, lame, s.data());
  SingularValueEnergy out;
  out.energy = k.energy;
  out.gradient = Eigen::Vector3d(k.gradient[0], k.gradient[1], k.gradient[2]);
  out.hessian = Eigen::Map<const Eigen::Matrix3d>(k.hessian.a);
  return out;
}

}  // namespace galsculpt
