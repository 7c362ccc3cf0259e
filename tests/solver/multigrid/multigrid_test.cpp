#include "solver/multigrid/multigrid.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/step.h"
#include "solver/model/sim_model.h"
#include "solver/multigrid/multigrid_cycle.h"
#include "solver/multigrid/multigrid_layout.h"
#include "tests/gpu/device_like_executor.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

using test::gridBar;

// The backward-Euler matrix M/h^2 + K of a deformed, hanging bar.
struct System {
  SimModel model;
  BlockSparseMatrix a;
  Eigen::VectorXd b;
};

System elasticitySystem(int nx = 3, int ny = 12, int nz = 3) {
  System s{
      buildSimModel(gridBar(nx, ny, nz, 0.02),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.45), 1000.0, {}}),
      BlockSparseMatrix(BlockPattern{}), Eigen::VectorXd()};
  s.a = BlockSparseMatrix(s.model.pattern);
  SimState state = initialState(s.model);
  for (int v = 0; v < s.model.numVertices(); ++v) {
    const Vec3 p = s.model.mesh.vertices[v];
    state.x[v] +=
        0.01 * Vec3(std::sin(20 * p.y()), 0.3 * std::cos(13 * p.x()), std::sin(7 * p.z() + p.y()));
  }
  Eigen::VectorXd g;
  assembleElastic(s.model, state.x, state, g, &s.a);
  const double h = 1.0 / 60.0;
  for (int v = 0; v < s.model.numVertices(); ++v) {
    s.a.blocks[s.model.pattern.diagonal[v]] +=
        s.model.mass[v] / (h * h) * Eigen::Matrix3d::Identity();
  }
  s.b = -g;
  for (int v = 0; v < s.model.numVertices(); ++v)
    s.b.segment<3>(3 * v) += s.model.mass[v] * Vec3(0, -9.81, 0);
  return s;
}

// The hierarchy's solve (multigrid_cycle.h) on the CPU executor, on a System's matrix.
struct Cycle {
  CpuExecutor ex;
  MultigridCycle<CpuExecutor> cycle;
  const System& system;
  std::vector<double> a;  // the fine blocks, 9 doubles each

  Cycle(const System& s, const Multigrid& mg, bool coarseCholesky = false)
      : cycle(ex, s.model.pattern), system(s) {
    cycle.upload(buildMultigridLayout(mg, s.model.pattern));
    for (const Eigen::Matrix3d& blk : s.a.blocks) a.insert(a.end(), blk.data(), blk.data() + 9);
    cycle.refresh(a.data(), coarseCholesky);
  }
  static MultigridCycle<CpuExecutor>::Settings settings(int cycles = 1) {
    MultigridCycle<CpuExecutor>::Settings st;
    st.cycles = cycles;
    return st;
  }
  // |b - A x| / |b| after the cycles from x = 0.
  double solve(Eigen::VectorXd& x, const MultigridCycle<CpuExecutor>::Settings& st) {
    x = Eigen::VectorXd::Zero(system.b.size());
    cycle.cycles(a.data(), system.b.data(), x.data(), st);
    return relativeResidual(x);
  }
  double relativeResidual(const Eigen::VectorXd& x) const {
    Eigen::VectorXd ax;
    system.a.multiply(x, ax);
    return (system.b - ax).norm() / system.b.norm();
  }
};

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
  jacobi.coarseCholesky = true;
  jacobi.jacobi = true;
  EXPECT_LT(c.solve(x, jacobi), 1e-3) << "Jacobi smoothing converges too, slower";
  MultigridCycle<CpuExecutor>::Settings cg = Cycle::settings(10);
  EXPECT_LT(c.solve(x, cg), 1e-3) << "and the coarse CG as well as the Cholesky";
}

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
    st.coarseCholesky = true;
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

// Under PCG the fine smoother keeps its own single-precision copy of the fine operator, taken
// at each refresh: its product agrees with the double one to float precision, and a cycle after
// a new refresh solves the new operator, not the old one. (The V-cycle tests above run the
// double-precision smoother; PCG still reaches the direct solution with the float one.)
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

TEST(Multigrid, SolvesAreDeterministic) {
  const System s = elasticitySystem();
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {60});
  Cycle c(s, mg);
  Eigen::VectorXd a, b;
  c.solve(a, Cycle::settings());
  c.solve(b, Cycle::settings());
  EXPECT_EQ(a, b);
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

// Slices cut off the top of a bar of elasticitySystem(3, 200, 3): 90 cuts between vertex
// layers, every second one (many small fragments side by side).
std::vector<std::uint8_t> slicedTop(const System& s) {
  std::vector<std::uint8_t> damaged(s.model.numEdges(), 0);
  for (int e = 0; e < s.model.numEdges(); ++e) {
    const double y0 = s.model.mesh.vertices[s.model.edges[e][0]].y();
    const double y1 = s.model.mesh.vertices[s.model.edges[e][1]].y();
    for (int cut = 0; cut < 90; ++cut) {
      const double y = 0.3 + 0.04 * cut + 0.01;
      if ((y0 - y) * (y1 - y) < 0.0) damaged[e] = 1;
    }
  }
  return damaged;
}

// Slices cut off the top of a bar (small fragments, no coarse handle), then one slice crumbled
// into loose vertices: the handles do not change, yet the fragments do. They follow the damage,
// the same as a hierarchy that saw the final damage at once (a frame depends on the damage, not
// on the order it came in: kept from before, a fresh solver, a reopened project's, ran on
// differently from the one that had stepped through the damage).
TEST(Multigrid, FragmentsFollowTheDamageWhereTheHandlesDoNot) {
  const System s = elasticitySystem(3, 200, 3);
  const std::vector<std::uint8_t> sliced = slicedTop(s);
  std::vector<std::uint8_t> crumbled = sliced;
  for (int e = 0; e < s.model.numEdges(); ++e) {
    const double y0 = s.model.mesh.vertices[s.model.edges[e][0]].y();
    if (y0 > 0.31 && y0 < 0.35) crumbled[e] = 1;  // every edge of the first slice
  }
  Multigrid stepwise(s.model.pattern, s.model.mesh.vertices, s.model.edges, {20});
  ASSERT_TRUE(stepwise.updateDamage(s.model.edges, sliced, 1));
  const size_t slicedFragments = stepwise.fragmentStart().size() - 1;
  const int handles = stepwise.level(0).handles;
  EXPECT_TRUE(stepwise.updateDamage(s.model.edges, crumbled, 2)) << "the fragments changed";
  EXPECT_EQ(stepwise.level(0).handles, handles) << "(the handles did not)";
  Multigrid atOnce(s.model.pattern, s.model.mesh.vertices, s.model.edges, {20});
  ASSERT_TRUE(atOnce.updateDamage(s.model.edges, crumbled, 1));
  EXPECT_EQ(atOnce.fragmentStart().size() - 1, slicedFragments - 1) << "one slice is gone";
  EXPECT_EQ(stepwise.fragmentStart(), atOnce.fragmentStart());
  EXPECT_EQ(stepwise.fragmentVertices(), atOnce.fragmentVertices());
}

// Many small fragments next to each other (slices cut off the top of a bar): their corrections
// run in parallel, and each reads its neighbours' positions, so they must not depend on which
// thread moved a neighbour first. The same solve with 1 and 2 threads, bit for bit (an app
// session replayed headless differed in its last bits before).
TEST(Multigrid, FragmentCorrectionsDoNotDependOnTheThreadCount) {
  const System s = elasticitySystem(3, 200, 3);
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {20});
  const std::vector<std::uint8_t> damaged = slicedTop(s);
  ASSERT_TRUE(mg.updateDamage(s.model.edges, damaged, 1));
  ASSERT_GE(mg.fragmentStart().size(), 80u) << "many fragments, more than a thread's chunk";
  const int threads = threadCount();
  setThreadCount(1);
  Cycle c(s, mg);
  Eigen::VectorXd serial;
  c.solve(serial, Cycle::settings());
  setThreadCount(2);
  for (int run = 0; run < 20; ++run) {
    Eigen::VectorXd parallel;
    c.solve(parallel, Cycle::settings());
    EXPECT_TRUE(parallel == serial) << "run " << run << ": " << (parallel - serial).norm();
  }
  setThreadCount(threads);
}

}  // namespace
}  // namespace galsculpt
