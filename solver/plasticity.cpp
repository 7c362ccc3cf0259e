#include "plasticity.h"

#include <cmath>

namespace galsculpt {

bool plasticReturn(const Lame& lame, const PlasticParams& params, const Eigen::Matrix3d& f,
                   Eigen::Matrix3d& fpInverse, double& plasticStrain) {
  if (params.yieldStress <= 0.0) return false;
  const Eigen::Matrix3d fe = f * fpInverse;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(fe, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  if (sigma.minCoeff() <= 1e-6) return false;  // collapsed or inverted: no flow from here
  const Eigen::Vector3d logStrain = sigma.array().log().matrix();
  const double mean = logStrain.mean();
  const Eigen::Vector3d deviator = logStrain - Eigen::Vector3d::Constant(mean);
  const double deviatorNorm = deviator.norm();
  // Deviatoric Kirchhoff stress 2 mu e_dev; von Mises q = sqrt(3/2) |s|.
  const double q = std::sqrt(1.5) * 2.0 * lame.mu * deviatorNorm;
  const double yield = params.yieldStress + params.hardening * plasticStrain;
  if (q <= yield || deviatorNorm <= 0.0) return false;
  const double gamma = (q - yield) / (3.0 * lame.mu + params.hardening);
  const Eigen::Vector3d newDeviator = deviator * (1.0 - 3.0 * lame.mu * gamma / q);
  plasticStrain += gamma;
  const Eigen::Vector3d newSigma = (newDeviator.array() + mean).exp().matrix();
  const Eigen::Matrix3d feNew = svd.matrixU() * newSigma.asDiagonal() * svd.matrixV().transpose();
  // F = Fe Fp  =>  Fp^-1 = F^-1 Fe.
  fpInverse = f.inverse() * feNew;
  // Keep the flow isochoric against round-off.
  const double det = fpInverse.determinant();
  if (det > 0.0) fpInverse /= std::cbrt(det);
  return true;
}

TetRest plasticRest(const TetRest& rest, const Eigen::Matrix3d& fpInverse) {
  // Rest edges from vertex 0 are the columns of Dm; the plastic rest shape is Fp Dm.
  const Eigen::Matrix3d dm = rest.dmInverse.inverse();
  const Eigen::Matrix3d plasticDm = fpInverse.inverse() * dm;
  TetPoints p{Eigen::Vector3d::Zero(), plasticDm.col(0), plasticDm.col(1), plasticDm.col(2)};
  TetRest r = computeTetRest(p);
  r.volume = rest.volume;  // isochoric flow: the energy keeps its rest volume
  return r;
}

}  // namespace galsculpt
