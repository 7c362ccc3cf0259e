// Hyperelastic energies written in the singular values of F, with exact first and second
// derivatives. Co-rotational linear, St. Venant-Kirchhoff and stable neo-Hookean are all
// isotropic, so each is a function Psi(s1, s2, s3) of the (signed) singular values; the element
// code turns these into P(F) and an exactly projected dP/dF through the analytic eigensystem
// (twist, flip and scaling modes). Formulas and reasons: docs/physics.md.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "solver/fem/material_types.h"

namespace galsculpt {

Lame lameFromYoungPoisson(double youngsModulus, double poissonRatio);
// Young's modulus of the Lame parameters (the inverse of lameFromYoungPoisson's first half).
double youngsModulus(const Lame& lame);

struct SingularValueEnergy {
  double energy = 0.0;                                 // per unit rest volume (J/m^3)
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // dPsi/ds_i
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();   // d2Psi/ds_i ds_j
};

// `s` are the signed singular values (s3 < 0 for an inverted element).
SingularValueEnergy evaluateSingularValueEnergy(MaterialModel model, const Lame& lame,
                                                const Eigen::Vector3d& s);

}  // namespace galsculpt
