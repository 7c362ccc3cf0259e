#include "solver/multigrid/multigrid.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "solver/frame/cpu_executor.h"
#include "solver/multigrid/multigrid_cycle.h"
#include "solver/multigrid/multigrid_layout.h"
#include "solver/frame/device_like_executor.h"
#include "tests/solver/multigrid/multigrid_fixture.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

using test::Cycle;
using test::elasticitySystem;
using test::gridBar;
using test::System;

TEST(Multigrid, ParsesGridSetups) {
  EXPECT_EQ(parseGridSetup("50/all"), std::vector<int>{50});
  EXPECT_EQ(parseGridSetup("50/1000/all"), (std::vector<int>{1000, 50}));
  EXPECT_THROW(parseGridSetup("1000/50/all"), std::invalid_argument);
  EXPECT_THROW(parseGridSetup("50"), std::invalid_argument);
}

TEST(Multigrid, FarthestPointSamplingIsGeodesicAndDeterministic) {
  const TetMesh bar = gridBar(1, 20, 1, 0.1);
  const std::vector<Edge> edges = uniqueEdges(bar);
  std::vector<int> all(bar.vertices.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  std::vector<int> nearest;
  const std::vector<int> samples = farthestPointSamples(bar.vertices, edges, all, 3, &nearest);
  ASSERT_EQ(samples.size(), 3u);
  // The first two samples sit at opposite ends of the bar; the third near the middle.
  const double y0 = bar.vertices[samples[0]].y(), y1 = bar.vertices[samples[1]].y();
  EXPECT_NEAR(std::abs(y0 - y1), 2.0, 1e-12);
  EXPECT_NEAR(bar.vertices[samples[2]].y(), 1.0, 0.11);
  for (size_t v = 0; v < bar.vertices.size(); ++v) {
    ASSERT_GE(nearest[v], 0);
    ASSERT_LT(nearest[v], 3);
  }
  std::vector<int> again;
  EXPECT_EQ(farthestPointSamples(bar.vertices, edges, all, 3, &again), samples);
  EXPECT_EQ(again, nearest);
}

TEST(Multigrid, ProlongationHasOneBlockPerFineRow) {
  const System s = elasticitySystem();
  const Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {40, 6});
  const Eigen::MatrixXd u = mg.prolongationMatrix(0);
  for (int r = 0; r < s.model.numVertices(); ++r) {
    int blocks = 0;
    for (int h = 0; h < mg.level(0).handles; ++h)
      blocks += u.block(3 * r, 12 * h, 3, 12).norm() > 0.0;
    EXPECT_EQ(blocks, 1);
  }
  const Eigen::MatrixXd u2 = mg.prolongationMatrix(1);
  for (int a = 0; a < mg.level(0).handles; ++a) {
    int blocks = 0;
    for (int h = 0; h < mg.level(1).handles; ++h)
      blocks += u2.block(12 * a, 12 * h, 12, 12).norm() > 0.0;
    EXPECT_EQ(blocks, 1);
  }
}

TEST(Multigrid, CoarseOperatorsAreGalerkinProductsAndPositiveDefinite) {
  // 150 handles on ~200 vertices: many single-vertex aggregates that cannot carry 12 DOFs.
  for (const std::vector<int>& counts : {std::vector<int>{40, 6}, std::vector<int>{150, 30}}) {
    const System s = elasticitySystem();
    Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, counts);
    Cycle c(s, mg);
    const Eigen::MatrixXd a = Eigen::MatrixXd(s.a.toEigen());
    const Eigen::MatrixXd u = mg.prolongationMatrix(0);
    const Eigen::MatrixXd a1 = c.cycle.coarseMatrix(1);
    const Eigen::MatrixXd galerkin = u.transpose() * a * u;
    EXPECT_LT((a1 - galerkin).norm(), 1e-8 * galerkin.norm())
        << "up to the tiny regularizing shift";
    EXPECT_LT((a1 - a1.transpose()).norm(), 1e-10 * a1.norm());
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(a1).info(), Eigen::Success);
    const Eigen::MatrixXd a2 = c.cycle.coarseMatrix(2);
    const Eigen::MatrixXd u2 = mg.prolongationMatrix(1);
    EXPECT_LT((a2 - u2.transpose() * a1 * u2).norm(), 1e-8 * a2.norm());
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(a2).info(), Eigen::Success);
  }
}

// A device builds the coarse levels a thread per entry, multiplies them and restricts to them a
// thread per row entry (DeviceLikeExecutor: the CUDA executor's paths on the CPU); the host a
// thread per block and per row. Both sum the same terms in the same order: the same bits, on both
// coarse levels.
TEST(Multigrid, DeviceShapedGalerkinProductsAndCoarseProductsGiveTheHostsBits) {
  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {150, 30});
  const MultigridLayout layout = buildMultigridLayout(mg, s.model.pattern);
  std::vector<double> a;
  for (const Eigen::Matrix3d& blk : s.a.blocks) a.insert(a.end(), blk.data(), blk.data() + 9);
  std::vector<std::uint8_t> fixed(s.model.numVertices(), 0);
  for (int v = 0; v < s.model.numVertices(); v += 7) fixed[v] = 1;
  CpuExecutor hostEx;
  DeviceLikeExecutor deviceEx;
  MultigridCycle<CpuExecutor> host(hostEx, s.model.pattern);
  MultigridCycle<DeviceLikeExecutor> device(deviceEx, s.model.pattern);
  host.upload(layout);
  device.upload(layout);
  host.setFixed(fixed.data());
  device.setFixed(fixed.data());
  host.refresh(a.data(), false);
  device.refresh(a.data(), false);
  for (int l = 1; l <= 2; ++l) {
    const Eigen::MatrixXd h = host.coarseMatrix(l), d = device.coarseMatrix(l);
    ASSERT_GT(h.norm(), 0.0);
    EXPECT_TRUE(h == d) << "level " << l << ": " << (h - d).norm();
    std::vector<double> x(h.rows()), yh(h.rows()), yd(h.rows());
    for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.7 * static_cast<double>(i));
    host.multiplyCoarse(l - 1, x.data(), yh.data());
    device.multiplyCoarse(l - 1, x.data(), yd.data());
    EXPECT_TRUE(yh == yd) << "level " << l;
  }
  // The restriction of a residual to each coarse level.
  for (int l = 0; l < 2; ++l) {
    const int rows =
        l == 0 ? 3 * s.model.numVertices() : static_cast<int>(host.coarseMatrix(l).rows());
    const int coarseRows = static_cast<int>(host.coarseMatrix(l + 1).rows());
    std::vector<double> b(rows), ax(rows), ch(coarseRows), cd(coarseRows);
    for (int i = 0; i < rows; ++i) {
      b[i] = std::cos(0.3 * i);
      ax[i] = 0.1 * std::sin(1.1 * i);
    }
    host.restrictResidual(l, b.data(), ax.data(), ch.data());
    device.restrictResidual(l, b.data(), ax.data(), cd.data());
    EXPECT_TRUE(ch == cd) << "restricted to level " << l + 1;
  }
}

TEST(Multigrid, AffineMotionsArePreservedByProlongation) {
  // A coarse correction that is the same affine map on every handle moves the fine mesh
  // affinely: the skinning space holds rigid and linear motions exactly.
  const System s = elasticitySystem();
  const Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {30});
  const Eigen::MatrixXd u = mg.prolongationMatrix(0);
  Eigen::Matrix<double, 3, 4> t;
  t << 0.1, 0.2, -0.3, 0.01, 0.05, -0.1, 0.2, 0.02, 0.3, 0.1, 0.0, -0.03;
  Eigen::VectorXd q(12 * mg.level(0).handles);
  const double scale =
      (s.model.mesh.vertices[mg.level(0).handleVertex[0]] - s.model.mesh.vertices[0]).norm();
  (void)scale;
  // Per handle: T_j acting on (x - c_j)/s + 1 must equal the global map G x + g0.
  for (int h = 0; h < mg.level(0).handles; ++h) {
    // Find s from any member: y = (x - c)/s.
    int member = -1;
    for (int v = 0; v < s.model.numVertices(); ++v)
      if (mg.level(0).parent[v] == h && v != mg.level(0).handleVertex[h]) member = v;
    const Vec3 c = s.model.mesh.vertices[mg.level(0).handleVertex[h]];
    double sc = 1.0;
    if (member >= 0)
      sc = (s.model.mesh.vertices[member] - c).norm() / mg.level(0).y[member].head<3>().norm();
    Eigen::Matrix<double, 3, 4> th;
    th.leftCols<3>() = t.leftCols<3>() * sc;
    th.col(3) = t.leftCols<3>() * c + t.col(3);
    q.segment<12>(12 * h) = Eigen::Map<const Eigen::Matrix<double, 12, 1>>(th.data());
  }
  const Eigen::VectorXd fine = u * q;
  for (int v = 0; v < s.model.numVertices(); ++v) {
    const Vec3 expected = t.leftCols<3>() * s.model.mesh.vertices[v] + t.col(3);
    EXPECT_LT((fine.segment<3>(3 * v) - expected).norm(), 1e-12);
  }
}

// Damage splits aggregates into their connected parts (each part its own handle, one U block
// per row still), loose vertices get no handle at all, and the coarse matrices stay SPD.
TEST(Multigrid, DamageSplitsAggregatesAndLeavesLooseVerticesToTheSmoother) {
  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {8});
  const int baseHandles = mg.level(0).handles;
  std::vector<std::uint8_t> damaged(s.model.numEdges(), 0);
  EXPECT_FALSE(mg.updateDamage(s.model.edges, damaged, 1)) << "no damage, no change";
  // Cut the bar across at y = 0.12 (between vertex layers) and free vertex 0 entirely.
  for (int e = 0; e < s.model.numEdges(); ++e) {
    const Edge& ed = s.model.edges[e];
    const double y0 = s.model.mesh.vertices[ed[0]].y(), y1 = s.model.mesh.vertices[ed[1]].y();
    if ((y0 - 0.11) * (y1 - 0.11) < 0.0 || ed[0] == 0 || ed[1] == 0) damaged[e] = 1;
  }
  EXPECT_TRUE(mg.updateDamage(s.model.edges, damaged, 2));
  EXPECT_FALSE(mg.updateDamage(s.model.edges, damaged, 2)) << "same revision: nothing to do";
  const MultigridLevel& level = mg.level(0);
  EXPECT_GT(level.handles, baseHandles) << "the aggregate across the cut is split";
  EXPECT_EQ(level.parent[0], -1) << "a loose vertex gets no coarse handle";
  // No aggregate holds vertices from both sides of the cut.
  for (int h = 0; h < level.handles; ++h) {
    int below = 0, above = 0;
    for (int v : level.members[h]) (s.model.mesh.vertices[v].y() < 0.11 ? below : above) += 1;
    EXPECT_TRUE(below == 0 || above == 0) << "handle " << h;
  }
  // U: one block per fine row that has a handle, none for the loose vertex.
  const Eigen::MatrixXd u = mg.prolongationMatrix(0);
  EXPECT_EQ(u.topRows(3).norm(), 0.0);
  for (int v = 1; v < s.model.numVertices(); ++v) {
    int blocks = 0;
    for (int h = 0; h < level.handles; ++h) blocks += u.block(3 * v, 12 * h, 3, 12).norm() > 0.0;
    EXPECT_EQ(blocks, 1) << "vertex " << v;
  }
  const Eigen::MatrixXd coarse = Cycle(s, mg).cycle.coarseMatrix(1);
  EXPECT_LT((coarse - coarse.transpose()).norm(), 1e-9 * coarse.norm());
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(coarse).info(), Eigen::Success);
  // Undoing the damage (a fresh revision with none) restores the base hierarchy.
  std::fill(damaged.begin(), damaged.end(), 0);
  EXPECT_TRUE(mg.updateDamage(s.model.edges, damaged, 3));
  EXPECT_EQ(mg.level(0).handles, baseHandles);
}

}  // namespace
}  // namespace galsculpt
