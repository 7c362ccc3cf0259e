// One element pass (solver/frame/element_pass.h) through its launches (element_launches.h, here
// the CPU executor's instantiation that the backend links): every element's energy, gradient and
// packed stiffness as the scalar kernel evaluates it, the same bits through the SIMD lanes, kept
// stiffnesses where F moved less than the tolerance, and the pieces' start's and the fracture
// pass's launches as their kernels evaluate them.
#include "solver/frame/element_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "solver/fem/tet_element.h"
#include "solver/frame/accelerated_start.h"
#include "solver/frame/cpu_executor.h"
#include "solver/model/sim_model.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

struct Bar {
  SimModel model =
      buildSimModel(test::gridBar(4, 2, 2, 0.01),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(2e5, 0.45), 1000.0, {}});
  std::vector<int> tetVertices, tetEdges;
  std::vector<std::uint8_t> damaged = std::vector<std::uint8_t>(model.numEdges(), 0);
  std::vector<double> y;
  Bar() {
    for (int t = 0; t < model.numTets(); ++t) {
      for (int a = 0; a < 4; ++a) tetVertices.push_back(model.mesh.tets[t][a]);
      for (int e = 0; e < 6; ++e) tetEdges.push_back(model.tetEdges[t][e]);
    }
    // Bent and twisted, some elements cracked.
    for (const Vec3& p : model.mesh.vertices) {
      const double c = std::cos(8.0 * p.x()), s = std::sin(8.0 * p.x());
      y.insert(y.end(),
               {p.x() * 1.05, c * p.y() - s * p.z() + 0.3 * p.x() * p.x(), s * p.y() + c * p.z()});
    }
    for (int e = 0; e < model.numEdges(); e += 7) damaged[e] = 1;
  }
  ElementInputs inputs() const {
    return {tetVertices.data(),
            tetEdges.data(),
            damaged.data(),
            model.rest.data(),
            nullptr,
            nullptr,
            nullptr};
  }
};

struct PassBuffers {
  std::vector<double> energy, inverted, gradient, packed, keptF;
  std::vector<std::uint8_t> fresh, opened;
  explicit PassBuffers(int tets)
      : energy(tets),
        inverted(tets),
        gradient(12 * tets),
        packed(90 * tets),
        keptF(9 * tets, std::nan("")),
        fresh(tets),
        opened(tets) {}
  ElementPass pass(const Bar& bar, kernels::Hessian mode, double keep) {
    return {bar.inputs(),
            bar.y.data(),
            energy.data(),
            inverted.data(),
            gradient.data(),
            packed.data(),
            bar.model.material.model,
            bar.model.material.lame,
            true,
            mode,
            keep,
            keptF.data(),
            fresh.data(),
            opened.data(),
            nullptr};
  }
};

TEST(ElementPass, EveryElementIsTheScalarKernelsAndTheLanesGiveItsBits) {
  const Bar bar;
  const int tets = bar.model.numTets();
  CpuExecutor ex;
  PassBuffers scalar(tets), laned(tets);
  launchElementPass(ex, scalar.pass(bar, kernels::Hessian::ProjectedSpd, 0.0), tets, nullptr,
                    nullptr);
  const kernels::LaneBuild build = kernels::chosenLaneBuild();
  launchElementPass(ex, laned.pass(bar, kernels::Hessian::ProjectedSpd, 0.0), tets,
                    kernels::laneKernel(build), kernels::crackedLaneKernel(build));
  EXPECT_EQ(laned.energy, scalar.energy);
  EXPECT_EQ(laned.gradient, scalar.gradient);
  EXPECT_EQ(laned.packed, scalar.packed);
  // Each element as tet_element.h evaluates it: energy, force and the packed upper blocks.
  for (int t = 0; t < tets; ++t) {
    TetPoints x;
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) x[a][k] = bar.y[3 * bar.tetVertices[4 * t + a] + k];
    ElementEval e;
    evaluateElement(bar.model.material.model, bar.model.material.lame, bar.model.rest[t], x,
                    tetDamage(bar.model, bar.damaged, t, true), HessianMode::ProjectedSpd, e);
    ASSERT_EQ(scalar.energy[t], e.energy) << "element " << t;
    for (int i = 0; i < 12; ++i) ASSERT_EQ(scalar.gradient[12 * t + i], e.gradient[i]);
    if (ElementPass::zeroStiffness(scalar.opened[t])) continue;
    for (int a = 0; a < 4; ++a)
      for (int c = a; c < 4; ++c)
        for (int j = 0; j < 3; ++j)
          for (int r = 0; r < 3; ++r)
            ASSERT_EQ(scalar.packed[90 * t + 9 * ElementPass::packedBlock(a, c) + r + 3 * j],
                      e.hessian(3 * a + r, 3 * c + j));
  }
}

// A trial's pass (no stiffness) through the lanes, and a pass where only some elements are
// evaluated: the scalar kernel's bits, and the elements left out untouched. For a model with its
// stress in closed form (the bar's) and one without (Hencky, whose trials take the lanes).
TEST(ElementPass, ATrialsLanesGiveTheScalarKernelsBitsAndOnlyTheFlaggedElementsAreEvaluated) {
  const Bar bar;
  const int tets = bar.model.numTets();
  CpuExecutor ex;
  const kernels::LaneBuild build = kernels::chosenLaneBuild();
  ASSERT_NE(kernels::laneKernel(build), nullptr) << "this test needs the lanes";
  std::vector<std::uint8_t> only(tets);
  for (int t = 0; t < tets; ++t) only[t] = t % 3 != 0;
  for (MaterialModel model : {bar.model.material.model, MaterialModel::Hencky}) {
    PassBuffers scalar(tets), laned(tets);
    ElementPass reference = scalar.pass(bar, kernels::Hessian::None, 0.0);
    reference.model = model;
    launchElementPass(ex, reference, tets, nullptr, nullptr);
    const double sentinel = -7.0;
    std::fill(laned.energy.begin(), laned.energy.end(), sentinel);
    std::fill(laned.packed.begin(), laned.packed.end(), sentinel);
    ElementPass pass = laned.pass(bar, kernels::Hessian::None, 0.0);
    pass.model = model;
    pass.only = only.data();
    launchElementPass(ex, pass, tets, kernels::laneKernel(build), nullptr);
    for (int t = 0; t < tets; ++t) {
      if (!only[t]) {
        ASSERT_EQ(laned.energy[t], sentinel) << "element " << t << " was left out";
        continue;
      }
      ASSERT_EQ(laned.energy[t], scalar.energy[t]) << "element " << t;
      for (int i = 0; i < 12; ++i)
        ASSERT_EQ(laned.gradient[12 * t + i], scalar.gradient[12 * t + i]) << "element " << t;
    }
    for (double v : laned.packed) ASSERT_EQ(v, sentinel) << "a trial writes no stiffness";
  }
}

TEST(ElementPass, AStiffnessIsKeptWhileFMovesLessThanTheToleranceAndOnlyIntactOnes) {
  Bar bar;
  const int tets = bar.model.numTets();
  CpuExecutor ex;
  PassBuffers buffers(tets);
  launchElementPass(ex, buffers.pass(bar, kernels::Hessian::ProjectedSpd, 1e-3), tets, nullptr,
                    nullptr);
  for (std::uint8_t f : buffers.fresh) ASSERT_EQ(f, 1) << "nothing to keep the first time";
  const std::vector<double> packed = buffers.packed;
  for (double& v : bar.y) v += 1e-6;  // a translation: F unchanged but for round-off
  launchElementPass(ex, buffers.pass(bar, kernels::Hessian::ProjectedSpd, 1e-3), tets, nullptr,
                    nullptr);
  int kept = 0;
  for (int t = 0; t < tets; ++t) {
    std::uint8_t intact = 0;
    for (int e = 0; e < 6; ++e)
      if (!bar.damaged[bar.tetEdges[6 * t + e]]) intact |= 1u << e;
    EXPECT_EQ(buffers.fresh[t], intact == kernels::kIntact ? 0 : 1) << "element " << t;
    if (buffers.fresh[t]) continue;
    ++kept;
    for (int i = 0; i < 90; ++i)
      ASSERT_EQ(buffers.packed[90 * t + i], packed[90 * t + i]) << "a kept stiffness is kept";
  }
  EXPECT_GT(kept, 0);
}

TEST(ElementPass, ThePiecesAndTheFractureLaunchesEvaluateTheirElements) {
  const Bar bar;
  const int tets = bar.model.numTets();
  CpuExecutor ex;
  const ElementModel element{bar.inputs(), bar.model.material.model, bar.model.material.lame, true};
  PassBuffers pass(tets);
  launchElementPass(ex, pass.pass(bar, kernels::Hessian::None, 0.0), tets, nullptr, nullptr);
  // Every third element read; the others' slots untouched.
  std::vector<int> shared, corners;
  for (int t = 0; t < tets; ++t) {
    shared.push_back(t);
    for (int c = 0; c < 4; ++c) corners.push_back(t % 3 == 0 ? 0 : 1);
  }
  const std::uint8_t heldPiece[2] = {0, 1};
  std::vector<double> gradients(12 * tets, -7.0);
  launchElementGradients(ex, element, SharedElements{shared.data(), corners.data(), heldPiece},
                         tets, bar.y.data(), gradients.data());
  for (int t = 0; t < tets; ++t)
    for (int i = 0; i < 12; ++i)
      ASSERT_EQ(gradients[12 * t + i], t % 3 == 0 ? pass.gradient[12 * t + i] : -7.0);
  std::vector<double> stress(6 * tets);
  launchEdgeNormalStress(ex, element, tets, bar.y.data(), stress.data());
  for (int t = 0; t < tets; ++t) {
    TetPoints x;
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) x[a][k] = bar.y[3 * bar.tetVertices[4 * t + a] + k];
    const std::array<double, 6> expected =
        edgeNormalStress(bar.model.material.model, bar.model.material.lame, bar.model.rest[t], x,
                         tetDamage(bar.model, bar.damaged, t, true));
    for (int e = 0; e < 6; ++e) ASSERT_EQ(stress[6 * t + e], expected[e]) << "element " << t;
  }
}

}  // namespace
}  // namespace galsculpt
