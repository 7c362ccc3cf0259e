#include "solver/fem/plasticity.h"

#include <stdexcept>

#include "solver/fem/element_kernels.h"

namespace galsculpt {

// Both run the shared element kernels (element_kernels.h), as the CUDA backend does.
bool plasticReturn(const Lame& lame, const PlasticParams& params, const Eigen::Matrix3d& f,
                   Eigen::Matrix3d& fpInverse, double& plasticStrain, bool flowsCollapsed) {
  kernels::M3 fk, fp;
  for (int i = 0; i < 9; ++i) {
    fk.a[i] = f.data()[i];
    fp.a[i] = fpInverse.data()[i];
  }
  const bool flowed = kernels::plasticReturn(
      lame, kernels::PlasticParamsData{params.yieldStress, params.hardening, flowsCollapsed}, fk,
      fp, plasticStrain);
  if (flowed) fpInverse = Eigen::Map<const Eigen::Matrix3d>(fp.a);
  return flowed;
}

TetRest plasticRest(const TetRest& rest, const Eigen::Matrix3d& fpInverse) {
  kernels::M3 fp;
  for (int i = 0; i < 9; ++i) fp.a[i] = fpInverse.data()[i];
  TetRest out;
  if (!kernels::plasticRest(rest, fp, out))
    throw std::invalid_argument("degenerate plastic rest shape");
  return out;
}

}  // namespace galsculpt
