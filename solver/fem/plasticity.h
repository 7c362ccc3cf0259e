// Multiplicative plasticity (clay): F = Fe Fp, von Mises yield on the Hencky strain of Fe with
// linear isotropic hardening, volume-preserving flow (det Fp = 1).
//
// After each step the elastic part is projected back onto the yield surface (radial return in
// principal logarithmic strains); the excess becomes permanent in Fp, so a dent stays after the
// tool lets go. The element then measures its energy from the plastically deformed rest shape.
#pragma once

#include <Eigen/Dense>

#include "solver/fem/isotropic_material.h"
#include "solver/fem/tet_element.h"

namespace galsculpt {

struct PlasticParams {
  double yieldStress = 0.0;  // Pa (von Mises); 0 disables plasticity
  double hardening = 0.0;    // Pa, linear isotropic hardening modulus
};

// Projects F Fp^-1 onto the yield surface; updates fpInverse and the accumulated plastic
// strain. Returns true when the element flowed. `flowsCollapsed`: as
// kernels::PlasticParamsData's (true for a model whose energy includes the flow).
bool plasticReturn(const Lame& lame, const PlasticParams& params, const Eigen::Matrix3d& f,
                   Eigen::Matrix3d& fpInverse, double& plasticStrain, bool flowsCollapsed = false);

// The rest data of an element whose rest shape has been deformed plastically by Fp.
TetRest plasticRest(const TetRest& rest, const Eigen::Matrix3d& fpInverse);

}  // namespace galsculpt
