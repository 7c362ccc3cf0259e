#include "solver/multigrid/multigrid_cycle.h"

#include <gtest/gtest.h>

#include "solver/frame/cpu_executor.h"
#include "solver/multigrid/multigrid_cycle.h"
#include "tests/solver/multigrid/multigrid_fixture.h"

namespace galsculpt {
namespace {

using test::Cycle;
using test::elasticitySystem;
using test::System;

// The coarsest level's direct solve, dense up to 64 handles and sparse on the host above
// (coarse_cholesky.h; a cracked body's split handles), is exact either way.
TEST(Multigrid, TheCoarsestLevelIsSolvedExactlyDenseOrSparse) {
  const System s = elasticitySystem();
  for (const int handles : {40, 100}) {
    SCOPED_TRACE(std::to_string(handles) + " handles");
    Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {handles});
    Cycle c(s, mg, true);
    ASSERT_EQ(c.cycle.numLevels(), 1);
    const Eigen::MatrixXd coarse = c.cycle.coarseMatrix(1);
    ASSERT_EQ(coarse.rows(), 12 * handles);
    EXPECT_EQ(MultigridCycle<CpuExecutor>::sparseCoarsest(handles), handles > 64);
    Eigen::VectorXd b(coarse.rows()), x(coarse.rows());
    for (int i = 0; i < b.size(); ++i) b[i] = std::sin(0.7 * i) * coarse(i, i);
    MultigridCycle<CpuExecutor>::Settings st = Cycle::settings();
    st.coarseCholesky = true;
    c.cycle.solveCoarsest(b.data(), x.data(), st);
    const Eigen::VectorXd exact = coarse.ldlt().solve(b);
    EXPECT_LT((x - exact).norm(), 1e-8 * exact.norm());
    EXPECT_LT((coarse * x - b).norm(), 1e-8 * b.norm());
  }
}

TEST(Multigrid, SolvesAreDeterministic) {
  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60});
  Cycle c(s, mg);
  Eigen::VectorXd a, b;
  c.solve(a, Cycle::settings());
  c.solve(b, Cycle::settings());
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace galsculpt
