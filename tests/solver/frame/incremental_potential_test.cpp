// The incremental potential (solver/frame/incremental_potential.h) on the CPU executor, on a
// small bar under gravity with mass damping, a plane collider under it, one vertex held and two
// pulled by soft anchors' springs:
// the backward-Euler gradient g against central differences of the potential, the Newton system
// H against central differences of g (stretched, where the projected stiffness is the exact
// one), the potential whole against the sum of the vertices' shares, and the trial's scalars
// and residual.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/frame/contact_term.h"
#include "solver/frame/cpu_executor.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/incremental_potential.h"
#include "solver/frame/plastic_state.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

struct Potential {
  SimModel model;
  CpuExecutor ex;
  FrameData<CpuExecutor> d;
  PlasticState<CpuExecutor> plastic;
  IncrementalPotential<CpuExecutor> potential;
  StepSettings settings;
  int n;

  static SimModel bar() {
    MaterialParams material{
        MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}};
    material.dampingMass = 0.7;
    SimModel m = buildSimModel(test::gridBar(4, 1, 1, 0.01), material);
    Collider plane;
    plane.point = Vec3(0, 0.0043, 0);  // the bar's lower vertices inside it
    plane.normal = Vec3(0.2, 1, 0).normalized();
    m.colliders.push_back(plane);
    return m;
  }

  Potential()
      : model(bar()),
        d(model),
        plastic(ex, model),
        potential(ex, model, d, plastic),
        n(model.numVertices()) {
    d.settings = &settings;
    d.h = 0.01;
    potential.contact().place({ColliderState{}}, 0.0, d.h);
    std::vector<double> x(3 * n), v(3 * n);
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        x[3 * i + k] = model.mesh.vertices[i][k];
        v[3 * i + k] = 0.05 * u(gen);
      }
    std::vector<double> xhat(3 * n);
    for (int i = 0; i < 3 * n; ++i) xhat[i] = x[i] + d.h * v[i];
    d.xn.upload(x);
    d.xhat.upload(xhat);
    std::vector<std::uint8_t> fixed(n, 0);
    fixed[0] = 1;
    d.fixed.upload(fixed);
    std::vector<double> springK(n, 0.0), springTarget(3 * n, 0.0);
    springK[3] = 500.0;
    springK[7] = 1200.0;
    for (const int v : {3, 7})
      for (int k = 0; k < 3; ++k) springTarget[3 * v + k] = x[3 * v + k] + 0.002 * (k + 1);
    d.springK.upload(springK);
    d.springTarget.upload(springTarget);
  }

  // The potential at y (the pass terms, as at a trial, and damping evaluated there).
  double at(const std::vector<double>& y) {
    std::vector<double> dampedK(3 * n);
    potential.passTerms().atTrial(y.data(), nullptr);
    potential.dampedProduct(y.data(), dampedK.data());
    potential.objective(y.data(), true, dampedK.data(), &d.sc()->e1);
    return d.sc()->e1;
  }
  // g at y, zero on the held vertex (the pass terms as at Newton's iterate).
  std::vector<double> g(const std::vector<double>& y) {
    std::vector<double> gradient(3 * n), dampedK(3 * n), out(3 * n);
    potential.passTerms().atIterate(y.data(), false, gradient.data());
    potential.dampedProduct(y.data(), dampedK.data());
    potential.backwardEulerGradient(y.data(), gradient.data(), dampedK.data(), out.data());
    return out;
  }
  // The rest shape stretched by `stretch`, each coordinate moved by up to `amplitude`.
  std::vector<double> near(double stretch, double amplitude, int seed) const {
    std::vector<double> y(3 * n);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) y[3 * i + k] = stretch * model.mesh.vertices[i][k] + u(gen);
    return y;
  }
};

TEST(IncrementalPotential, GradientIsTheDerivativeOfThePotential) {
  Potential p;
  const std::vector<double> y = p.near(1.0, 5e-4, 1);
  const std::vector<double> g = p.g(y);
  const double h = 1e-8;
  double largest = 0.0;
  for (double x : g) largest = std::max(largest, std::abs(x));
  ASSERT_GT(largest, 0.0);
  for (int i = 3; i < 3 * p.n; ++i) {  // vertex 0 is held: its g is zero
    std::vector<double> yp = y, ym = y;
    yp[i] += h;
    ym[i] -= h;
    const double fd = (p.at(yp) - p.at(ym)) / (2 * h);
    EXPECT_NEAR(g[i], fd, 1e-5 * largest) << "coordinate " << i;
  }
  for (int k = 0; k < 3; ++k) EXPECT_EQ(g[k], 0.0) << "the held vertex";
}

TEST(IncrementalPotential, SystemIsTheDerivativeOfTheGradient) {
  Potential p;
  // Stretched by 1 %: every mode of every element's stiffness is then positive, so the system's
  // SPD projection is the exact Hessian (at rest the twist modes' eigenvalues are zero, and a
  // small disturbance turns some negative: projected, they differ from it).
  const std::vector<double> y = p.near(1.01, 1e-6, 2);
  p.g(y);  // the stiffness at y
  p.potential.buildSystem(y.data());
  std::vector<double> blocks(p.d.system.size());
  p.ex.download(p.d.system.data(), blocks.data(), blocks.size());
  const BlockPattern& pattern = p.model.pattern;
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> dir(3 * p.n);
  for (int i = 3; i < 3 * p.n; ++i) dir[i] = u(gen);  // not moving the held vertex
  std::vector<double> hv(3 * p.n, 0.0);
  for (int r = 0; r < p.n; ++r)
    for (int k = pattern.rowStart[r]; k < pattern.rowStart[r + 1]; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          hv[3 * r + i] += blocks[9 * k + i + 3 * j] * dir[3 * pattern.columns[k] + j];
  const double eps = 1e-7;
  std::vector<double> yp = y, ym = y;
  for (int i = 0; i < 3 * p.n; ++i) {
    yp[i] += eps * dir[i];
    ym[i] -= eps * dir[i];
  }
  const std::vector<double> gp = p.g(yp), gm = p.g(ym);
  double largest = 0.0;
  for (double x : hv) largest = std::max(largest, std::abs(x));
  for (int i = 3; i < 3 * p.n; ++i)
    EXPECT_NEAR(hv[i], (gp[i] - gm[i]) / (2 * eps), 1e-5 * largest) << "coordinate " << i;
}

TEST(IncrementalPotential, VertexSharesSumToThePotential) {
  Potential p;
  const std::vector<double> y = p.near(1.0, 5e-4, 4);
  const double whole = p.at(y);
  std::vector<double> dampedK(3 * p.n), shares(p.n);
  p.potential.dampedProduct(y.data(), dampedK.data());
  p.potential.vertexPotential(y.data(), true, dampedK.data(), shares.data());
  double sum = 0.0;
  for (double s : shares) sum += s;
  EXPECT_NEAR(sum, whole, 1e-12 * std::abs(whole) + 1e-15);
}

// Where the frame tests the residual between Newton iterations (residualAtTrials), a trial
// forms the residual there too; accepted, it is the accepted positions' bit for bit (g, the pass
// terms' forces, both sums), so the frame's residual test takes the line search's last read and
// waits for nothing of its own. Without a residual test, trials form none.
TEST(IncrementalPotential, ATrialsResidualIsTheAcceptedPositionsBitForBit) {
  Potential p;
  p.settings.newtonIterations = 8;
  p.settings.residualTolerance = 0.01;
  ASSERT_TRUE(p.potential.residualAtTrials());
  const int size = 3 * p.n;
  p.d.x.upload(p.near(1.0, 5e-4, 6));
  p.d.delta.upload(p.near(0.0, 2e-4, 7));
  p.potential.evaluateTrial(0.5);
  const FrameScalars trial = *p.d.sc();
  std::vector<double> trialG(size), trialForces(size);
  p.ex.download(p.d.trialG.data(), trialG.data(), size);
  p.ex.download(p.d.trialForces.data(), trialForces.data(), size);
  // Accepted as the frame accepts a trial (frame_solver.h, newtonIteration).
  p.ex.copy(p.d.x.data(), p.d.trial.data(), size);
  p.ex.copy(p.d.acceptedGrad.data(), p.d.trialGrad.data(), size);
  p.potential.acceptedResidual();
  const FrameScalars accepted = *p.d.sc();
  std::vector<double> g(size), forces(size);
  p.ex.download(p.d.g.data(), g.data(), size);
  p.ex.download(p.d.tmp.data(), forces.data(), size);
  EXPECT_GT(trial.trialResidual, 0.0);
  EXPECT_GT(trial.trialForceScale, 0.0);
  EXPECT_EQ(trial.trialResidual, accepted.residual);
  EXPECT_EQ(trial.trialForceScale, accepted.forceScale);
  EXPECT_EQ(trialG, g);
  EXPECT_EQ(trialForces, forces);

  p.settings.residualTolerance = 0.0;
  p.settings.reuseStiffness = false;
  EXPECT_FALSE(p.potential.residualAtTrials()) << "the reference tests its step, not a residual";
  p.settings.residualTolerance = 0.01;
  p.settings.newtonIterations = 1;
  EXPECT_FALSE(p.potential.residualAtTrials()) << "one iteration: no test between iterations";
}

}  // namespace
}  // namespace galsculpt
