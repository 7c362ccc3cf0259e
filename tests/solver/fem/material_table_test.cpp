// The table of material models (solver/fem/material_table.h): one row per model, each name used
// once; each model's closed form in F (where it has one) is the same material as its energy in
// the singular values; fixed corotated, the model added through the table alone, has the
// analytic derivatives its finite differences give; and docs/scenes.md lists every row.
#include "solver/fem/material_table.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "solver/fem/isotropic_material.h"
#include "solver/fem/material_kernels.h"

namespace galsculpt {
namespace {

using kernels::M3;

TEST(MaterialTable, OneRowPerModelAndEachNameOnce) {
  std::set<std::string> names;
  std::set<MaterialModel> models;
  for (const MaterialInfo& row : kMaterialModels) {
    names.insert(row.name);
    models.insert(row.model);
    EXPECT_EQ(&materialInfo(row.model), &row);
    EXPECT_GT(std::string(row.summary).size(), 20u) << row.name;
  }
  EXPECT_EQ(names.size(), std::size(kMaterialModels));
  EXPECT_EQ(models.size(), std::size(kMaterialModels));
  EXPECT_EQ(models.size(), static_cast<size_t>(MaterialModel::Hencky) + 1)
      << "every enum value has its row";
}

// directStress is the energy-only path of the line search: for a model with a closed form it
// must be the model of its singular-value energy (a model without one goes through the SVD).
TEST(MaterialTable, DirectStressIsTheSingularValueModel) {
  const Lame lame = lameFromYoungPoisson(1e5, 0.4);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (const MaterialInfo& row : kMaterialModels) {
    for (int trial = 0; trial < 20; ++trial) {
      M3 f{};
      for (int i = 0; i < 9; ++i) f.a[i] = (i % 4 == 0 ? 1.0 : 0.0) + u(gen);
      if (trial == 0) f.a[0] = -0.5;  // inverted
      double psi = 0.0;
      const M3 p = kernels::directStress(row.model, lame, f, psi);
      M3 uu, vv;
      double s[3];
      kernels::rotationVariantSvd(f, uu, s, vv);
      const kernels::SingularValueEnergy e = kernels::singularValueEnergy(row.model, lame, s);
      const M3 expected = kernels::scaledProduct(uu, e.gradient, vv);
      const double scale = lame.mu + lame.lambda;
      EXPECT_NEAR(psi, e.energy, 1e-9 * scale) << row.name;
      for (int i = 0; i < 9; ++i) EXPECT_NEAR(p.a[i], expected.a[i], 1e-9 * scale) << row.name;
    }
  }
}

// Fixed corotated, analytically: rest is stress free; at s the energy, gradient and Hessian
// against the formula and against central differences.
TEST(MaterialTable, FixedCorotatedMatchesItsFormulaAndFiniteDifferences) {
  const Lame lame{2.0, 3.0};
  const double s[3] = {1.3, 0.8, 0.6};
  const kernels::SingularValueEnergy e =
      kernels::singularValueEnergy(MaterialModel::FixedCorotated, lame, s);
  const double j = s[0] * s[1] * s[2];
  double expected = 0.5 * lame.lambda * (j - 1) * (j - 1);
  for (double si : s) expected += lame.mu * (si - 1) * (si - 1);
  EXPECT_NEAR(e.energy, expected, 1e-14);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i) {
    double sp[3] = {s[0], s[1], s[2]}, sm[3] = {s[0], s[1], s[2]};
    sp[i] += h;
    sm[i] -= h;
    const auto ep = kernels::singularValueEnergy(MaterialModel::FixedCorotated, lame, sp);
    const auto em = kernels::singularValueEnergy(MaterialModel::FixedCorotated, lame, sm);
    EXPECT_NEAR(e.gradient[i], (ep.energy - em.energy) / (2 * h), 1e-8);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(e.hessian(i, k), (ep.gradient[k] - em.gradient[k]) / (2 * h), 1e-7);
  }
  const double one[3] = {1.0, 1.0, 1.0};
  const auto rest = kernels::singularValueEnergy(MaterialModel::FixedCorotated, lame, one);
  EXPECT_EQ(rest.energy, 0.0);
  for (double g : rest.gradient) EXPECT_EQ(g, 0.0);
  EXPECT_FALSE(kernels::hasDirectStress(MaterialModel::FixedCorotated));
  EXPECT_TRUE(kernels::hasDirectStress(MaterialModel::StableNeoHookean));
}

// Half the volume: fixed corotated pushes back with its volume term, as stable neo-Hookean does.
TEST(MaterialTable, FixedCorotatedResistsStrongCompression) {
  const Lame lame = lameFromYoungPoisson(1e5, 0.45);
  const double c = std::cbrt(0.5);
  const double s[3] = {c, c, c};
  for (MaterialModel m : {MaterialModel::FixedCorotated, MaterialModel::StableNeoHookean}) {
    const auto e = kernels::singularValueEnergy(m, lame, s);
    EXPECT_GT(e.energy, 0.0);
    for (double g : e.gradient) EXPECT_LT(g, 0.0) << "pushes outwards: the energy falls as s grows";
  }
}

TEST(MaterialTable, TheScenesPageListsEveryModel) {
  std::ifstream in(std::string(GALSCULPT_SOURCE_DIR) + "/docs/scenes.md");
  ASSERT_TRUE(in) << "docs/scenes.md";
  std::stringstream text;
  text << in.rdbuf();
  for (const MaterialInfo& row : kMaterialModels) {
    const std::string line = std::string("| `") + row.name + "` | " + row.summary + " |";
    EXPECT_NE(text.str().find(line), std::string::npos) << "docs/scenes.md lacks: " << line;
  }
}

}  // namespace
}  // namespace galsculpt
