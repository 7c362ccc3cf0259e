// The plastic return (solver/fem/plasticity.h) against J2 flow with linear hardening in closed
// form: an isochoric stretch F = diag(s, 1/sqrt s, 1/sqrt s) has the trial von Mises stress
// q = 3 mu ln s; past the yield stress the return leaves q = yield + H gamma with
// gamma = (q - yield) / (3 mu + H), the volume unchanged and the direction of flow the stretch's.
#include "solver/fem/plasticity.h"

#include <gtest/gtest.h>

#include <cmath>

namespace galsculpt {
namespace {

constexpr Lame kLame{1e5, 4e5};

Eigen::Matrix3d isochoricStretch(double s) {
  return Eigen::DiagonalMatrix<double, 3>(s, 1.0 / std::sqrt(s), 1.0 / std::sqrt(s))
      .toDenseMatrix();
}

// The von Mises stress of the elastic part F Fp^-1 (Hencky strains, deviatoric part).
double vonMises(const Eigen::Matrix3d& fe) {
  // log of the singular values, from the eigenvalues of Fe^T Fe (log s = log(lambda) / 2).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(fe.transpose() * fe);
  Eigen::Vector3d e = 0.5 * eigen.eigenvalues().array().log();
  e.array() -= e.mean();
  return std::sqrt(1.5) * 2.0 * kLame.mu * e.norm();
}

TEST(Plasticity, AStretchPastYieldReturnsToTheHardenedSurfaceInClosedForm) {
  for (const double hardening : {0.0, 2e4, 2e5}) {
    const PlasticParams params{1e4, hardening};
    const Eigen::Matrix3d f = isochoricStretch(1.2);
    Eigen::Matrix3d fpInverse = Eigen::Matrix3d::Identity();
    double strain = 0.0;
    ASSERT_TRUE(plasticReturn(kLame, params, f, fpInverse, strain));
    const double trial = 3.0 * kLame.mu * std::log(1.2);
    const double gamma = (trial - params.yieldStress) / (3.0 * kLame.mu + hardening);
    EXPECT_NEAR(strain, gamma, 1e-12 * gamma) << "hardening " << hardening;
    EXPECT_NEAR(vonMises(f * fpInverse), params.yieldStress + hardening * gamma,
                1e-9 * params.yieldStress);
    EXPECT_NEAR(fpInverse.determinant(), 1.0, 1e-12) << "the flow keeps the volume";
    // The flow is along the stretch: Fp^-1 is diagonal, shortening the stretched axis.
    EXPECT_NEAR(fpInverse(0, 1), 0.0, 1e-12);
    EXPECT_LT(fpInverse(0, 0), 1.0);
    // On the surface now: the same F flows no further than round-off.
    const Eigen::Matrix3d returned = fpInverse;
    const double returnedStrain = strain;
    plasticReturn(kLame, params, f, fpInverse, strain);
    EXPECT_LT((fpInverse - returned).norm(), 1e-12);
    EXPECT_LT(strain - returnedStrain, 1e-12 * gamma);
  }
}

TEST(Plasticity, BelowYieldOrWithoutAYieldStressNothingFlows) {
  const Eigen::Matrix3d f = isochoricStretch(1.01);  // q = 3 mu ln 1.01 ~ 2985 Pa
  Eigen::Matrix3d fpInverse = Eigen::Matrix3d::Identity();
  double strain = 0.0;
  EXPECT_FALSE(plasticReturn(kLame, {1e4, 0.0}, f, fpInverse, strain));
  EXPECT_FALSE(plasticReturn(kLame, {0.0, 0.0}, isochoricStretch(2.0), fpInverse, strain));
  EXPECT_EQ(fpInverse, Eigen::Matrix3d::Identity());
  EXPECT_EQ(strain, 0.0);
  // A pure volume change has no deviator: no flow however large.
  EXPECT_FALSE(
      plasticReturn(kLame, {1e4, 0.0}, 1.5 * Eigen::Matrix3d::Identity(), fpInverse, strain));
}

TEST(Plasticity, ThePlasticRestShapeKeepsTheVolumeAndRefusesADegenerateOne) {
  const TetPoints p = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                       Eigen::Vector3d(0, 0, 1)};
  const TetRest rest = computeTetRest(p);
  const Eigen::Matrix3d fpInverse = isochoricStretch(1.3).inverse();
  const TetRest flowed = plasticRest(rest, fpInverse);
  EXPECT_DOUBLE_EQ(flowed.volume, rest.volume);
  // The deformation gradient at the flowed rest shape of x = Fp X is the identity.
  const Eigen::Matrix3d fp = fpInverse.inverse();
  TetPoints x;
  for (int a = 0; a < 4; ++a) x[a] = fp * p[a];
  const Eigen::Matrix3d f = deformationGradient(flowed, x);
  EXPECT_LT((f - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_THROW(plasticRest(rest, Eigen::Matrix3d::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace galsculpt
