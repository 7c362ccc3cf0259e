// The Newton system's solve (solver/frame/linear_solve.h) on a bar's backward-Euler system with
// one vertex held: PCG with the Galerkin multigrid to a tight tolerance gives CHOLMOD's step,
// a V-cycle reduces the residual it reports, the held vertex's step is zero, the null-step
// test says yes for g = 0 only, and a local iteration's solve is the direct solve of its rows.
#include "solver/frame/linear_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/device_like_executor.h"
#include "solver/frame/incremental_potential.h"
#include "solver/frame/plastic_state.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

template <typename Exec>
struct SystemOn {
  SimModel model =
      buildSimModel(test::gridBar(8, 2, 2, 0.01),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}});
  Exec ex;
  FrameData<Exec> d{model};
  PlasticState<Exec> plastic{ex, model};
  IncrementalPotential<Exec> potential{ex, model, d, plastic};
  LinearSolve<Exec> linear{ex, model, d};
  StepSettings settings;
  std::vector<std::uint8_t> damaged = std::vector<std::uint8_t>(model.numEdges(), 0);
  int n = model.numVertices();

  SystemOn() {
    settings.type = SolverType::Multigrid;
    settings.gridHandles = {8};
    d.settings = &settings;
    d.h = 0.01;
    std::vector<double> x(3 * n);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) x[3 * i + k] = 1.01 * model.mesh.vertices[i][k];
    d.x.upload(x);
    d.xn.upload(x);
    d.xhat.upload(x);
    std::vector<std::uint8_t> fixed(n, 0);
    fixed[0] = 1;
    d.fixed.upload(fixed);
    std::vector<double> gradient(3 * n);
    FrameScalars* sc = d.sc();
    potential.elastic().evaluate(x.data(), true, gradient.data(), &sc->elastic, &sc->inverted);
    potential.buildSystem(x.data());
    std::vector<double> g(3 * n, 0.0);
    std::mt19937 gen(9);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 3; i < 3 * n; ++i) g[i] = 1e-3 * u(gen);
    d.g.upload(g);
    linear.ensureHierarchy(settings, damaged, 0);
  }
  std::vector<double> step() {
    std::vector<double> delta(3 * n);
    d.delta.download(delta.data(), delta.size());
    return delta;
  }
  // PCG's step to `tolerance` (relative), its iterations counted from zero; its figures from
  // the frame's scalars, read as the frame reads them after the step (takeSolve).
  std::vector<double> pcgStep(double tolerance) {
    settings.pcgTolerance = tolerance;
    linear.resetIterations();
    linear.solve(settings, 0.0);
    FrameScalars read;
    ex.read(d.sc(), &read, 1);
    linear.takeSolve(read);
    return step();
  }
};
using System = SystemOn<CpuExecutor>;

TEST(LinearSolve, PcgWithTheMultigridGivesTheDirectSolvesStep) {
  System s;
  s.linear.solveDirect(s.settings);
  const std::vector<double> direct = s.step();
  s.settings.pcgTolerance = 1e-6;  // (the refresh for a V-cycle that preconditions)
  s.linear.refresh(s.settings);
  const std::vector<double> pcg = s.pcgStep(1e-12);
  EXPECT_GT(s.linear.iterations(), 0);
  EXPECT_LT(s.linear.reduction(), 1e-11);
  // The figures wait in the frame's scalars until the frame's read: no read of their own.
  const int iterations = s.linear.iterations();
  s.linear.solve(s.settings, 0.0);
  EXPECT_EQ(s.linear.iterations(), iterations) << "not yet taken";
  FrameScalars read;
  s.ex.read(s.d.sc(), &read, 1);
  s.linear.takeSolve(read);
  EXPECT_EQ(s.linear.iterations(), 2 * iterations) << "the same solve again";
  EXPECT_EQ(read.pcgReduction, s.linear.reduction());
  s.linear.takeSolve(read);
  EXPECT_EQ(s.linear.iterations(), 2 * iterations) << "taken once";
  double largest = 0.0, difference = 0.0;
  for (int i = 0; i < 3 * s.n; ++i) {
    largest = std::max(largest, std::abs(direct[i]));
    difference = std::max(difference, std::abs(pcg[i] - direct[i]));
  }
  ASSERT_GT(largest, 0.0);
  EXPECT_LT(difference, 1e-9 * largest);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(pcg[k], 0.0) << "the held vertex";
}

// A local iteration's solve (region_solve.h): block-Jacobi PCG on the region's rows gives the
// direct solve of the system that holds every other vertex still, and moves nothing outside.
TEST(LinearSolve, ALocalSolveIsTheDirectSolveOfTheRegionsRows) {
  System s;
  std::vector<std::uint8_t> region(s.n, 0), regionFixed(s.n, 1);
  int inside = 0;
  for (int v = 1; v < s.n; ++v)
    if (s.model.mesh.vertices[v].x() < 0.035) {
      region[v] = 1;
      regionFixed[v] = 0;
      ++inside;
    }
  ASSERT_GT(inside, 10);
  ASSERT_LT(inside, s.n / 2);
  // The direct solve of the system that holds every vertex outside the region as an anchor.
  std::vector<std::uint8_t> held(s.n);
  s.d.fixed.download(held.data(), held.size());
  s.d.fixed.upload(regionFixed);
  s.potential.buildSystem(s.d.x.data());
  s.linear.solveDirect(s.settings);
  const std::vector<double> direct = s.step();
  s.d.fixed.upload(held);
  s.d.regionVertex.upload(region);
  s.d.regionFixed.upload(regionFixed);
  s.d.local = true;
  s.potential.buildSystem(s.d.x.data());
  const std::vector<double> local = s.pcgStep(1e-11);
  EXPECT_GT(s.linear.iterations(), 0);
  EXPECT_LT(s.linear.reduction(), 1e-10);
  double largest = 0.0, difference = 0.0;
  for (int v = 0; v < s.n; ++v)
    for (int k = 0; k < 3; ++k) {
      const int i = 3 * v + k;
      if (!region[v]) {
        ASSERT_EQ(local[i], 0.0) << "vertex " << v << " is held still";
        ASSERT_EQ(direct[i], 0.0) << "vertex " << v;
        continue;
      }
      largest = std::max(largest, std::abs(direct[i]));
      difference = std::max(difference, std::abs(local[i] - direct[i]));
    }
  ASSERT_GT(largest, 0.0);
  EXPECT_LT(difference, 1e-8 * largest);
}

TEST(LinearSolve, AVCycleReducesTheResidualItReports) {
  System s;
  s.linear.refresh(s.settings);
  s.linear.solve(s.settings, 0.0);
  FrameScalars read;
  s.ex.read(s.d.sc(), &read, 1);
  EXPECT_GT(read.r0, 0.0);
  EXPECT_LT(read.r1, 0.25 * read.r0) << "|b - A delta|^2 against |b|^2";
  for (int k = 0; k < 3; ++k) EXPECT_EQ(s.step()[k], 0.0) << "the held vertex";
}

TEST(LinearSolve, TheNullStepIsTakenOnlyForANullGradient) {
  System s;
  double bnorm = -1.0;
  EXPECT_FALSE(s.linear.nullStep(s.settings, 0.0, bnorm));
  EXPECT_GT(bnorm, 0.0);
  EXPECT_TRUE(s.linear.nullStep(s.settings, 2.0 * bnorm, bnorm)) << "within the target";
  s.d.g.upload(std::vector<double>(3 * s.n, 0.0));
  EXPECT_TRUE(s.linear.nullStep(s.settings, 0.0, bnorm));
  EXPECT_EQ(bnorm, 0.0);
  EXPECT_EQ(s.linear.reduction(), 0.0);
}

// A device factors the coarsest level without waiting for the status: it rides the frame's read
// after the solve, and a failure read there is said once (the step is then solved again, the
// coarsest level by CG, and that solve's read says nothing more).
TEST(LinearSolve, ADevicesCoarseFactorizationStatusRidesTheFramesRead) {
  SystemOn<DeviceLikeExecutor> s;
  s.settings.coarseSolver = CoarseSolver::Cholesky;
  s.settings.pcgTolerance = 1e-8;
  auto solveAndRead = [&] {
    s.linear.solve(s.settings, 0.0);
    FrameScalars read;
    s.ex.read(s.d.sc(), &read, 1);
    s.linear.takeSolve(read);
    return read;
  };
  long waits = s.ex.counters().waits;
  s.linear.refresh(s.settings);
  EXPECT_EQ(s.ex.counters().waits, waits) << "no wait for the factorization's status";
  FrameScalars read = solveAndRead();
  EXPECT_FALSE(s.linear.coarseFactorFailed(read));
  EXPECT_LT(s.linear.reduction(), 1e-8);
  // A system that is not positive definite: the dense factorization fails.
  const size_t entries = s.d.system.size();
  std::vector<double> system(entries);
  s.d.system.download(system.data(), entries);
  for (double& v : system) v = -v;
  s.d.system.upload(system);
  waits = s.ex.counters().waits;
  s.linear.refresh(s.settings);
  EXPECT_EQ(s.ex.counters().waits, waits);
  read = solveAndRead();
  EXPECT_EQ(read.coarseFailed, 1.0);
  EXPECT_TRUE(s.linear.coarseFactorFailed(read));
  EXPECT_FALSE(s.linear.coarseFactorFailed(read)) << "said once";
  read = solveAndRead();  // again, the coarsest level by CG
  EXPECT_FALSE(s.linear.coarseFactorFailed(read));
}

}  // namespace
}  // namespace galsculpt
