#include "solver/multigrid/multigrid_cycle.h"

#include <gtest/gtest.h>

#include "solver/frame/cpu_executor.h"
#include "solver/multigrid/multigrid_cycle.h"
#include "solver/frame/device_like_executor.h"
#include "tests/solver/multigrid/multigrid_fixture.h"

namespace galsculpt {
namespace {

using test::Cycle;
using test::elasticitySystem;
using test::System;

// The coarsest level's direct solve is exact on either side: factored by blocks in host memory
// (coarse_cholesky.h), whatever the handle count, and dense on a device (the device-like
// executor takes the device's path on the CPU).
template <typename Exec>
void expectCoarsestSolvedExactly(const System& s, const Multigrid& mg, int handles) {
  Exec ex;
  MultigridCycle<Exec> cycle(ex, s.model.pattern);
  cycle.upload(buildMultigridLayout(mg, s.model.pattern));
  std::vector<double> a;
  for (const Eigen::Matrix3d& blk : s.a.blocks) a.insert(a.end(), blk.data(), blk.data() + 9);
  cycle.refresh(a.data(), true);
  ASSERT_EQ(cycle.numLevels(), 1);
  const Eigen::MatrixXd coarse = cycle.coarseMatrix(1);
  ASSERT_EQ(coarse.rows(), 12 * handles);
  Eigen::VectorXd b(coarse.rows()), x(coarse.rows());
  for (int i = 0; i < b.size(); ++i) b[i] = std::sin(0.7 * i) * coarse(i, i);
  typename MultigridCycle<Exec>::Settings st;
  st.coarseSolver = CoarseSolver::Cholesky;
  cycle.solveCoarsest(b.data(), x.data(), st);
  const Eigen::VectorXd exact = coarse.ldlt().solve(b);
  EXPECT_LT((x - exact).norm(), 1e-8 * exact.norm());
  EXPECT_LT((coarse * x - b).norm(), 1e-8 * b.norm());
}

TEST(Multigrid, TheCoarsestLevelIsSolvedExactlyOnTheHostAndOnADevice) {
  const System s = elasticitySystem();
  for (const int handles : {40, 100}) {
    SCOPED_TRACE(std::to_string(handles) + " handles");
    Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {handles});
    {
      SCOPED_TRACE("host (blocks)");
      expectCoarsestSolvedExactly<CpuExecutor>(s, mg, handles);
    }
    {
      SCOPED_TRACE("device-like (dense)");
      expectCoarsestSolvedExactly<DeviceLikeExecutor>(s, mg, handles);
    }
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
