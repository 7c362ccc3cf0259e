#include "solver/multigrid/multigrid_pcg.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/device_like_executor.h"
#include "solver/multigrid/multigrid_cycle.h"
#include "tests/solver/multigrid/multigrid_fixture.h"

namespace galsculpt {
namespace {

using test::Cycle;
using test::elasticitySystem;
using test::System;

TEST(Multigrid, VCycleReducesTheResidualAndPcgReachesTheDirectSolution) {
  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60, 8});
  Cycle c(s, mg, true);  // factors the coarsest level too, for the Jacobi + Cholesky case
  Eigen::VectorXd x;
  const double one = c.solve(x, Cycle::settings(1));
  EXPECT_LT(one, 0.2) << "one V-cycle cuts the residual 5x";
  const double ten = c.solve(x, Cycle::settings(10));
  EXPECT_LT(ten, 1e-3);
  std::printf("one V-cycle: %.3g, ten: %.3g\n", one, ten);

  Eigen::VectorXd xp = Eigen::VectorXd::Zero(s.b.size());
  const auto pcg = c.cycle.pcg(c.a.data(), s.b.data(), xp.data(), Cycle::settings(), 1e-12, 30);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct(s.a.toEigen());
  const Eigen::VectorXd exact = direct.solve(s.b);
  EXPECT_LT(pcg.reduction, 1e-12) << "within 30 iterations";
  EXPECT_GT(pcg.iterations, 0);
  EXPECT_LE(pcg.iterations, 30);
  EXPECT_LT((xp - exact).norm(), 1e-9 * exact.norm());
  EXPECT_TRUE(xp.allFinite());
  // An absolute target stops it earlier, at that residual: what an inexact Newton step needs.
  const double bnorm = s.b.norm();
  const auto loose =
      c.cycle.pcg(c.a.data(), s.b.data(), xp.data(), Cycle::settings(), 1e-12, 30, 1e-4 * bnorm);
  EXPECT_LE(loose.reduction, 1e-4);
  EXPECT_LT(loose.iterations, pcg.iterations);
  EXPECT_LT((s.b - s.a.toEigen() * xp).norm(), 1.0001e-4 * bnorm) << "the residual it reports";

  MultigridCycle<CpuExecutor>::Settings jacobi = Cycle::settings(30);
  jacobi.coarseSolver = CoarseSolver::Cholesky;
  jacobi.smoother = Smoother::Jacobi;
  EXPECT_LT(c.solve(x, jacobi), 1e-3) << "Jacobi smoothing converges too, slower";
  MultigridCycle<CpuExecutor>::Settings cg = Cycle::settings(10);
  EXPECT_LT(c.solve(x, cg), 1e-3) << "and the coarse CG as well as the Cholesky";
}

// On a device PCG's iterations are a loop whose test the device makes (loopOnDevice): the host
// waits only for the result, or not at all (launch()), and the loop runs no iteration past the
// stop. With the V-cycle both executors share (Gauss-Seidel, CG on the coarsest level, doubles)
// it gives the host loop's bits: the same x, iterations and reduction.
TEST(MultigridPcg, TheDeviceLoopGivesTheHostLoopsBitsWithoutWaiting) {
  const System s = elasticitySystem();
  const Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60, 8});
  std::vector<double> a;
  for (const Eigen::Matrix3d& blk : s.a.blocks) a.insert(a.end(), blk.data(), blk.data() + 9);
  MultigridCycle<CpuExecutor>::Settings settings = solverPreset(SolverPreset::Converged);
  settings.smoother = Smoother::GaussSeidel;
  settings.coarseSolver = CoarseSolver::Cg;
  const int rows = s.model.numVertices();
  struct Run {
    std::vector<double> x;
    MultigridPcg<CpuExecutor>::Result result;
    DeviceCounters cost;  // of the solve
  };
  auto solve = [&]<typename Exec>(Exec& ex, const double* b, double tolerance, int most,
                                  bool read) {
    MultigridCycle<Exec> cycle(ex, s.model.pattern);
    cycle.upload(buildMultigridLayout(mg, s.model.pattern));
    cycle.refresh(a.data(), false, false);
    MultigridPcg<Exec> pcg(ex);
    Run run;
    run.x.assign(3 * rows, 1.0);
    ex.flush();  // the refresh's launches run apart
    const DeviceCounters before = ex.counters();
    if (read) {
      const auto r = pcg.solve(cycle, rows, a.data(), b, run.x.data(), settings, tolerance, most,
                               0.0, cycle.bakedKey(settings));
      run.result = {r.reduction, r.iterations};
    } else {
      pcg.launch(cycle, rows, a.data(), b, run.x.data(), settings, tolerance, most, 0.0,
                 cycle.bakedKey(settings));
    }
    ex.flush();
    const DeviceCounters after = ex.counters();
    run.cost.programs = after.kernels() - before.kernels();
    run.cost.barriers = after.barriers - before.barriers;
    run.cost.waits = after.waits - before.waits;
    return run;
  };
  CpuExecutor host;
  DeviceLikeExecutor device;
  const Run onHost = solve(host, s.b.data(), 1e-10, 60, true);
  const Run onDevice = solve(device, s.b.data(), 1e-10, 60, true);
  ASSERT_GT(onHost.result.iterations, 4);
  EXPECT_LT(onHost.result.reduction, 1e-10);
  EXPECT_EQ(onDevice.x, onHost.x);
  EXPECT_EQ(onDevice.result.iterations, onHost.result.iterations);
  EXPECT_EQ(onDevice.result.reduction, onHost.result.reduction);
  EXPECT_EQ(onDevice.cost.waits, 1) << "the result's read, and nothing in the iterations";
  EXPECT_EQ(onDevice.cost.programs, 1) << "the solve is one device program, its loop inside";
  const Run unread = solve(device, s.b.data(), 1e-10, 60, false);
  EXPECT_EQ(unread.x, onHost.x);
  EXPECT_EQ(unread.cost.waits, 0) << "launch() leaves the read to its caller";
  // No iteration past the stop: a solve capped at k iterations costs k passes, and the
  // converged one as many as its iterations.
  const Run one = solve(device, s.b.data(), 1e-14, 1, false),
            two = solve(device, s.b.data(), 1e-14, 2, false);
  const long pass = two.cost.barriers - one.cost.barriers;
  ASSERT_GT(pass, 0);
  EXPECT_EQ(unread.cost.barriers, one.cost.barriers + (onHost.result.iterations - 1) * pass);
  EXPECT_EQ(unread.cost.programs, 1);
  // Stopped by the iteration cap: the bits of the host's cap.
  const Run capped = solve(host, s.b.data(), 1e-14, 3, true),
            cappedOnDevice = solve(device, s.b.data(), 1e-14, 3, true);
  EXPECT_EQ(capped.result.iterations, 3);
  EXPECT_EQ(cappedOnDevice.result.iterations, 3);
  EXPECT_EQ(cappedOnDevice.x, capped.x);
  EXPECT_EQ(cappedOnDevice.result.reduction, capped.result.reduction);
  // Nothing to solve: no pass, x = 0.
  const std::vector<double> zero(3 * rows, 0.0);
  const Run none = solve(device, zero.data(), 1e-10, 60, true);
  EXPECT_EQ(none.result.iterations, 0);
  EXPECT_EQ(none.result.reduction, 0.0);
  EXPECT_EQ(none.x, zero);
  EXPECT_EQ(none.cost.barriers, one.cost.barriers - pass) << "the start's phases, no pass";
}

// What a device replays of a V-cycle is keyed by everything it bakes in: each setting the cycle
// reads, a new upload of the hierarchy, and the held vertices' array.
TEST(MultigridPcg, EverythingAVCycleBakesInChangesItsKey) {
  const System s = elasticitySystem();
  const Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60, 8});
  Cycle c(s, mg);
  const MultigridCycle<CpuExecutor>::Settings base = solverPreset(SolverPreset::Converged);
  const std::uint64_t key = c.cycle.bakedKey(base);
  EXPECT_EQ(c.cycle.bakedKey(base), key);
  std::vector<MultigridCycle<CpuExecutor>::Settings> changed(5, base);
  changed[0].fineSweeps += 1;
  changed[1].coarseIterations += 1;
  changed[2].smoother = Smoother::Jacobi;
  changed[3].coarseSolver = CoarseSolver::Cg;
  changed[4].pcgTolerance *= 2.0;
  for (size_t i = 0; i < changed.size(); ++i) EXPECT_NE(c.cycle.bakedKey(changed[i]), key) << i;
  const std::vector<std::uint8_t> held(s.model.numVertices(), 0);
  c.cycle.setFixed(held.data());
  const std::uint64_t withHeld = c.cycle.bakedKey(base);
  EXPECT_NE(withHeld, key) << "the held vertices' array";
  c.cycle.upload(buildMultigridLayout(mg, s.model.pattern));
  EXPECT_NE(c.cycle.bakedKey(base), withHeld) << "a new upload";
}

}  // namespace
}  // namespace galsculpt
