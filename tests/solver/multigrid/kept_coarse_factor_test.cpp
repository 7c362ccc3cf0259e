#include "solver/multigrid/kept_coarse_factor.h"

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

// Under PCG (the V-cycle only preconditions) the coarsest level keeps its factorization while
// its matrix stays within kCoarseReuse of the one factored, dense or sparse; a larger change, or
// a V-cycle that is the solver itself, factors it again. PCG reaches the direct solution either
// way: a kept factor changes the preconditioner, not the equations.
TEST(Multigrid, TheCoarsestFactorIsKeptOnlyWhileItsMatrixBarelyMoves) {
  const System s = elasticitySystem();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct(s.a.toEigen());
  const Eigen::VectorXd solution = direct.solve(s.b);
  for (const int handles : {40, 100}) {
    SCOPED_TRACE(std::to_string(handles) + " handles");
    Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {handles});
    Cycle c(s, mg, true);
    MultigridCycle<CpuExecutor>::Settings st = Cycle::settings();
    st.coarseSolver = CoarseSolver::Cholesky;
    const int n = 12 * handles;
    Eigen::VectorXd b(n), exact(n), x(n);
    for (int i = 0; i < n; ++i) b[i] = std::sin(0.7 * i) + 0.2;
    auto coarseError = [&] {
      exact = c.cycle.coarseMatrix(1).ldlt().solve(b);
      c.cycle.solveCoarsest(b.data(), x.data(), st);
      return (x - exact).norm() / exact.norm();
    };
    EXPECT_EQ(c.cycle.coarseFactorsKept(), 0);
    EXPECT_LT(coarseError(), 1e-10);
    c.cycle.refresh(c.a.data(), true, true);
    EXPECT_EQ(c.cycle.coarseFactorsKept(), 1) << "the same matrix: kept";
    EXPECT_LT(coarseError(), 1e-10);

    const std::vector<double> original = c.a;
    for (double& v : c.a) v *= 1.0 + 0.1 * MultigridCycle<CpuExecutor>::kCoarseReuse;
    c.cycle.refresh(c.a.data(), true, true);
    EXPECT_EQ(c.cycle.coarseFactorsKept(), 2) << "a tenth of the tolerance: kept";
    const double keptError = coarseError();
    EXPECT_GT(keptError, 1e-5) << "the old matrix's solve";
    EXPECT_LT(keptError, 2e-3);
    Eigen::VectorXd xp = Eigen::VectorXd::Zero(s.b.size());
    const std::vector<double> a = c.a;
    const double factor = 1.0 + 0.1 * MultigridCycle<CpuExecutor>::kCoarseReuse;
    const auto pcg = c.cycle.pcg(a.data(), s.b.data(), xp.data(), st, 1e-12, 40);
    EXPECT_LT(pcg.reduction, 1e-12);
    EXPECT_LT((factor * xp - solution).norm(), 1e-9 * solution.norm()) << "A (1 + d) x = b";

    for (double& v : c.a) v = 3.0 * v;
    c.cycle.refresh(c.a.data(), true, true);
    EXPECT_EQ(c.cycle.coarseFactorsKept(), 2) << "three times the matrix: factored again";
    EXPECT_LT(coarseError(), 1e-10);

    c.a = original;
    c.cycle.refresh(c.a.data(), true, false);
    c.cycle.refresh(c.a.data(), true, false);
    EXPECT_EQ(c.cycle.coarseFactorsKept(), 2) << "a V-cycle that solves alone is always exact";
    EXPECT_LT(coarseError(), 1e-10);
  }
}

}  // namespace
}  // namespace galsculpt
