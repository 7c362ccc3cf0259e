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

// On a device PCG reads its state once a batch of iterations; the iterations a batch runs past
// the stop change nothing, so batches of any length give the bits of stopping at once, with
// fewer host waits than iterations (host memory reads after each iteration).
TEST(MultigridPcg, BatchesOfAnyLengthGiveTheBitsOfStoppingAtOnce) {
  const System s = elasticitySystem();
  const Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60, 8});
  DeviceLikeExecutor ex;
  MultigridCycle<DeviceLikeExecutor> cycle(ex, s.model.pattern);
  cycle.upload(buildMultigridLayout(mg, s.model.pattern));
  std::vector<double> a;
  for (const Eigen::Matrix3d& blk : s.a.blocks) a.insert(a.end(), blk.data(), blk.data() + 9);
  cycle.refresh(a.data(), false, true);
  MultigridCycle<DeviceLikeExecutor>::Settings settings = solverPreset(SolverPreset::Converged);
  const int rows = s.model.numVertices();
  struct Run {
    std::vector<double> x;
    MultigridPcg<DeviceLikeExecutor>::Result result;
    long waits = 0;
  };
  auto solve = [&](int batch, double tolerance, int most) {
    MultigridPcg<DeviceLikeExecutor> pcg(ex);
    pcg.setFixedBatch(batch);
    Run run;
    run.x.assign(3 * rows, 0.0);
    const long before = ex.counters().waits;
    run.result =
        pcg.solve(cycle, rows, a.data(), s.b.data(), run.x.data(), settings, tolerance, most, 0.0);
    run.waits = ex.counters().waits - before;
    return run;
  };
  const Run one = solve(1, 1e-10, 60);
  ASSERT_GT(one.result.iterations, 4);
  EXPECT_LT(one.result.reduction, 1e-10);
  for (int batch : {2, 3, 7, 0}) {
    const Run run = solve(batch, 1e-10, 60);
    EXPECT_EQ(run.x, one.x) << "batch " << batch;
    EXPECT_EQ(run.result.iterations, one.result.iterations) << "batch " << batch;
    EXPECT_EQ(run.result.reduction, one.result.reduction) << "batch " << batch;
    EXPECT_LT(run.waits, one.waits) << "batch " << batch;
  }
  // Stopped by the iteration cap inside a batch: the bits of the cap.
  const Run capped = solve(1, 1e-14, 3), cappedInBatch = solve(7, 1e-14, 3);
  EXPECT_EQ(capped.result.iterations, 3);
  EXPECT_EQ(cappedInBatch.x, capped.x);
  EXPECT_EQ(cappedInBatch.result.reduction, capped.result.reduction);
  // Nothing to solve: no iteration, x = 0.
  std::vector<double> zero(3 * rows, 0.0), x(3 * rows, 1.0);
  MultigridPcg<DeviceLikeExecutor> pcg(ex);
  const auto none =
      pcg.solve(cycle, rows, a.data(), zero.data(), x.data(), settings, 1e-10, 60, 0.0);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_EQ(none.reduction, 0.0);
  EXPECT_EQ(x, zero);
}

}  // namespace
}  // namespace galsculpt
