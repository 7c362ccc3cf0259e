#include "solver/multigrid/fine_smoother.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "tests/solver/multigrid/multigrid_fixture.h"

namespace galsculpt {
namespace {

using test::Cycle;
using test::elasticitySystem;
using test::System;

// Under PCG the fine smoother keeps its own single-precision copy of the fine operator, taken
// at each refresh: its product agrees with the double one to float precision, and a cycle after
// a new refresh solves the new operator, not the old one. (The V-cycle tests of
// multigrid_cycle_test.cpp run the double-precision smoother; PCG still reaches the direct
// solution with the float one.)
TEST(Multigrid, TheSmoothersCopyOfTheFineOperatorFollowsEachRefresh) {
  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60});
  Cycle c(s, mg);
  const int n = static_cast<int>(s.b.size());
  c.cycle.refresh(c.a.data(), false, true);
  Eigen::VectorXd smoother(n), exact(n);
  c.cycle.multiplySmoother(c.a.data(), s.b.data(), smoother.data());
  c.cycle.multiplyFine(c.a.data(), s.b.data(), exact.data());
  EXPECT_LT((smoother - exact).norm(), 1e-6 * exact.norm());
  EXPECT_GT((smoother - exact).norm(), 0.0) << "(the copy is in single precision)";
  Eigen::VectorXd xp = Eigen::VectorXd::Zero(n);
  const auto pcg = c.cycle.pcg(c.a.data(), s.b.data(), xp.data(), Cycle::settings(), 1e-12, 30);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct(s.a.toEigen());
  const Eigen::VectorXd solution = direct.solve(s.b);
  EXPECT_LT(pcg.reduction, 1e-12) << "PCG is as exact with the float smoother";
  EXPECT_LT((xp - solution).norm(), 1e-9 * solution.norm());

  Eigen::VectorXd once;
  c.solve(once, Cycle::settings(3));
  for (double& v : c.a) v *= 2.0;  // a new operator, 2 A
  c.cycle.refresh(c.a.data(), false, true);
  Eigen::VectorXd twice = Eigen::VectorXd::Zero(n);
  c.cycle.cycles(c.a.data(), s.b.data(), twice.data(), Cycle::settings(3));
  EXPECT_LT((2.0 * twice - once).norm(), 1e-12 * once.norm()) << "cycles on 2 A give x / 2";
}

}  // namespace
}  // namespace galsculpt
