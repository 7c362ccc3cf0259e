#include "solver/multigrid/multigrid_pcg.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "solver/frame/cpu_executor.h"
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

}  // namespace
}  // namespace galsculpt
