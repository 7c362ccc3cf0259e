#include "solver/multigrid/fine_rows.h"

#include <gtest/gtest.h>

#include <cstring>

#include "solver/fem/element_lanes.h"
#include "tests/solver/multigrid/multigrid_fixture.h"

namespace galsculpt {
namespace {

using kernels::LaneBuild;
using test::Cycle;
using test::elasticitySystem;
using test::System;

struct SmootherResults {
  Eigen::VectorXd product, solution;
};

// The V-cycle's float-copy product and a few PCG iterations through its sweeps (stopped well
// before convergence, so that every sweep's bits reach the result), with the rows of a build.
SmootherResults smootherResults(const System& s, const Multigrid& mg, LaneBuild build) {
  kernels::setLaneBuild(build);
  Cycle c(s, mg);
  c.cycle.refresh(c.a.data(), false, true);
  const int n = static_cast<int>(s.b.size());
  SmootherResults out{Eigen::VectorXd(n), Eigen::VectorXd::Zero(n)};
  c.cycle.multiplySmoother(c.a.data(), s.b.data(), out.product.data());
  c.cycle.pcg(c.a.data(), s.b.data(), out.solution.data(), Cycle::settings(), 1e-14, 3);
  return out;
}

bool sameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

// The AVX2 rows are chosen with the element lanes' AVX2 build and round as the portable loops:
// the same product and the same solve, bit for bit.
TEST(FineRows, TheAvx2RowsGiveThePortableLoopsBits) {
  if (!kernels::laneKernel(LaneBuild::Avx2)) GTEST_SKIP() << "this CPU has no AVX2";
  const LaneBuild before = kernels::chosenLaneBuild();
  kernels::setLaneBuild(LaneBuild::Off);
  EXPECT_EQ(fine_rows::sweepRow(), nullptr);
  EXPECT_EQ(fine_rows::productRow(), nullptr);
  kernels::setLaneBuild(LaneBuild::Avx2);
  EXPECT_NE(fine_rows::sweepRow(), nullptr);
  EXPECT_NE(fine_rows::productRow(), nullptr);

  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60});
  const SmootherResults loops = smootherResults(s, mg, LaneBuild::Off);
  const SmootherResults rows = smootherResults(s, mg, LaneBuild::Avx2);
  kernels::setLaneBuild(before);
  EXPECT_TRUE(sameBits(loops.product, rows.product));
  EXPECT_TRUE(sameBits(loops.solution, rows.solution));
  EXPECT_GT(loops.solution.norm(), 0.0);
}

}  // namespace
}  // namespace galsculpt
