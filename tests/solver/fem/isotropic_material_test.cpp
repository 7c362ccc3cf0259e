#include "solver/fem/isotropic_material.h"

#include <gtest/gtest.h>

#include "solver/fem/material_table.h"

namespace galsculpt {
namespace {

TEST(IsotropicMaterial, LameParameters) {
  const Lame l = lameFromYoungPoisson(1000.0, 0.25);
  EXPECT_DOUBLE_EQ(l.mu, 1000.0 / 2.5);
  EXPECT_DOUBLE_EQ(l.lambda, 1000.0 * 0.25 / (1.25 * 0.5));
  for (const double nu : {-0.5, 0.0, 0.3, 0.49})
    EXPECT_NEAR(youngsModulus(lameFromYoungPoisson(2e11, nu)), 2e11, 1e-3) << "nu " << nu;
}

// At rest (s = 1) every model has zero energy and zero gradient; away from rest the analytic
// gradient and Hessian match central differences.
TEST(IsotropicMaterial, RestIsStressFreeAndDerivativesMatchFiniteDifferences) {
  const Lame lame = lameFromYoungPoisson(1e5, 0.4);
  for (const MaterialInfo& row : kMaterialModels) {  // every model of the table
    const MaterialModel m = row.model;
    const SingularValueEnergy rest = evaluateSingularValueEnergy(m, lame, Eigen::Vector3d::Ones());
    EXPECT_NEAR(rest.energy, 0.0, 1e-9 * lame.mu);
    EXPECT_LT(rest.gradient.norm(), 1e-9 * lame.mu);
    for (const Eigen::Vector3d& s :
         {Eigen::Vector3d(1.2, 0.9, 1.05), Eigen::Vector3d(0.7, 1.3, 0.8),
          Eigen::Vector3d(1.1, 1.0, -0.2)}) {
      const SingularValueEnergy e = evaluateSingularValueEnergy(m, lame, s);
      const double h = 1e-6;
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d sp = s, sm = s;
        sp[i] += h;
        sm[i] -= h;
        const SingularValueEnergy ep = evaluateSingularValueEnergy(m, lame, sp);
        const SingularValueEnergy em = evaluateSingularValueEnergy(m, lame, sm);
        const double scale = lame.mu + lame.lambda;
        EXPECT_NEAR(e.gradient[i], (ep.energy - em.energy) / (2 * h), 1e-5 * scale)
            << static_cast<int>(m) << " s " << s.transpose();
        for (int j = 0; j < 3; ++j)
          EXPECT_NEAR(e.hessian(i, j), (ep.gradient[j] - em.gradient[j]) / (2 * h), 1e-4 * scale)
              << static_cast<int>(m) << " s " << s.transpose();
      }
    }
  }
}

}  // namespace
}  // namespace galsculpt
