// The Hencky model with its flow in the energy (solver/fem/materials/hencky.h): central
// differences of an element's energy give its gradient and of the gradient its exact Hessian
// past the yield surface, crushed and inverted; the energy's stress is the stress of the state
// the return map commits (plasticReturn), so a converged step is in equilibrium after it; and a
// material point in uniaxial stress, loaded step by step through yield in tension and in
// compression, follows J2 flow with linear hardening in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/fem/isotropic_material.h"
#include "solver/fem/plasticity.h"
#include "solver/fem/tet_element.h"

namespace galsculpt {
namespace {

Lame plasticLame(double yield, double hardening) {
  Lame lame = lameFromYoungPoisson(2e5, 0.45);
  lame.yield = yield;
  lame.hardening = hardening;
  return lame;
}

TetPoints restTet() {
  return {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.0, 0.1, 0.0),
          Eigen::Vector3d(0.2, 0.9, 0.1), Eigen::Vector3d(0.1, 0.2, 1.1)};
}

TetPoints mapped(const TetPoints& rest, const Eigen::Matrix3d& f) {
  TetPoints x;
  for (int a = 0; a < 4; ++a) x[a] = f * rest[a];
  return x;
}

ElementEval eval(const Lame& lame, const TetRest& r, const TetPoints& x, HessianMode mode) {
  ElementEval out;
  evaluateElement(MaterialModel::Hencky, lame, r, x, EdgeDamage{}, mode, out);
  return out;
}

TEST(Hencky, DerivativesMatchFiniteDifferencesPastYieldCrushedAndInverted) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const Eigen::Matrix3d crushed = Eigen::Vector3d(1.3, 1.1, 0.05).asDiagonal();
  const Eigen::Matrix3d inverted = Eigen::Vector3d(1.2, 0.9, -0.3).asDiagonal();
  for (const double hardening : {0.0, 1e4}) {
    for (int trial = 0; trial < 8; ++trial) {
      Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
      for (int i = 0; i < 9; ++i) f.data()[i] += u(gen);
      if (trial == 6) f = crushed;
      if (trial == 7) f = inverted;
      SCOPED_TRACE(::testing::Message() << "H " << hardening << " trial " << trial);
      const Lame lame = plasticLame(2e3, hardening);
      const TetPoints x = mapped(rest, f);
      const ElementEval e = eval(lame, r, x, HessianMode::Exact);
      const ElementEval elastic = eval(plasticLame(0.0, 0.0), r, x, HessianMode::None);
      EXPECT_LT(e.energy, elastic.energy) << "past yield: the flow lowered the energy";
      const double h = 1e-7;
      Vec12 fdGradient;
      Mat12 fdHessian;
      for (int i = 0; i < 12; ++i) {
        TetPoints plus = x, minus = x;
        plus[i / 3][i % 3] += h;
        minus[i / 3][i % 3] -= h;
        const ElementEval ep = eval(lame, r, plus, HessianMode::None);
        const ElementEval em = eval(lame, r, minus, HessianMode::None);
        fdGradient[i] = (ep.energy - em.energy) / (2 * h);
        fdHessian.col(i) = (ep.gradient - em.gradient) / (2 * h);
      }
      const double gScale = std::max(1.0, e.gradient.norm());
      EXPECT_LT((fdGradient - e.gradient).norm(), 1e-6 * gScale);
      const double hScale = std::max(1.0, e.hessian.norm());
      EXPECT_LT((fdHessian - e.hessian).norm(), 1e-5 * hScale);
      const ElementEval spd = eval(lame, r, x, HessianMode::ProjectedSpd);
      const Eigen::SelfAdjointEigenSolver<Mat12> eig(spd.hessian);
      EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-8 * hScale);
    }
  }
}

// Kirchhoff stress P F^T of the model at F.
Eigen::Matrix3d kirchhoff(const Lame& lame, const Eigen::Matrix3d& f) {
  return firstPiolaStress(MaterialModel::Hencky, lame, f) * f.transpose();
}

TEST(Hencky, TheEnergysStressIsTheStressOfTheStateTheReturnCommits) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 9; ++i) f.data()[i] += u(gen);
    const PlasticParams params{2e3, 1e4};
    const Lame atStart = plasticLame(params.yieldStress, params.hardening);
    Eigen::Matrix3d fpInverse = Eigen::Matrix3d::Identity();
    double strain = 0.0;
    ASSERT_TRUE(plasticReturn(atStart, params, f, fpInverse, strain, true)) << trial;
    const Eigen::Matrix3d fe = f * fpInverse;
    // The committed elastic part, elastic (no yield), has the stress the energy gave at F.
    const Eigen::Matrix3d expected = kirchhoff(plasticLame(0.0, 0.0), fe);
    EXPECT_LT((kirchhoff(atStart, f) - expected).norm(), 1e-9 * expected.norm()) << trial;
    // And it sits on the hardened surface: evaluated with the grown yield stress it flows no
    // further, its stress unchanged.
    const Lame hardened = plasticLame(params.yieldStress + params.hardening * strain, 1e4);
    EXPECT_LT((kirchhoff(hardened, fe) - expected).norm(), 1e-9 * expected.norm()) << trial;
  }
}

// Uniaxial stress along x: the lateral stretch found by bisection so that the lateral stress
// vanishes, the axial Kirchhoff stress and accumulated plastic strain committed step by step,
// against J2 with linear hardening in the (additive) Hencky strains: tau = E eps below yield,
// tau = E (H eps + sigma_y) / (E + H) past it, eps_p = (E eps - sigma_y) / (E + H).
TEST(Hencky, UniaxialStressThroughYieldIsJ2WithLinearHardeningInClosedForm) {
  const double yield = 5e3;
  for (const double hardening : {0.0, 1e4, 1e5}) {
    for (const double sign : {1.0, -1.0}) {
      const Lame base = plasticLame(0.0, 0.0);
      const double youngs = youngsModulus(base);
      const PlasticParams params{yield, hardening};
      Eigen::Matrix3d fpInverse = Eigen::Matrix3d::Identity();
      double strain = 0.0;
      const int steps = 40;
      const double last = sign * 6.0 * yield / youngs;  // six times the yield strain
      for (int k = 1; k <= steps; ++k) {
        const double eps = last * k / steps;
        Lame lame = base;
        lame.yield = yield + hardening * strain;
        lame.hardening = hardening;
        auto stretchOf = [&](double lateral) {
          return Eigen::Vector3d(std::exp(eps), lateral, lateral).asDiagonal().toDenseMatrix();
        };
        double lo = 0.5, hi = 1.5;
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (lo + hi);
          (kirchhoff(lame, stretchOf(mid) * fpInverse)(1, 1) > 0.0 ? hi : lo) = mid;
        }
        const Eigen::Matrix3d f = stretchOf(0.5 * (lo + hi));
        const double tau = kirchhoff(lame, f * fpInverse)(0, 0);
        plasticReturn(lame, params, f, fpInverse, strain, true);
        const double magnitude = std::abs(eps);
        const bool plastic = youngs * magnitude > yield;
        const double expected =
            sign * (plastic ? youngs * (hardening * magnitude + yield) / (youngs + hardening)
                            : youngs * magnitude);
        const double expectedStrain =
            plastic ? (youngs * magnitude - yield) / (youngs + hardening) : 0.0;
        SCOPED_TRACE(::testing::Message()
                     << "H " << hardening << " sign " << sign << " step " << k);
        EXPECT_NEAR(tau, expected, 1e-6 * yield);
        EXPECT_NEAR(strain, expectedStrain, 1e-9);
      }
    }
  }
}

}  // namespace
}  // namespace galsculpt
