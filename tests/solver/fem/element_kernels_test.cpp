// The element kernels shared by the CPU and CUDA backends, called directly (plain arrays), as
// the device runs them: the two Hessian paths against each other, the cracks' opening, the rest
// data, and the plastic return (the 3x3 algebra's tests are kernel_math_test.cpp's).
#include "solver/fem/element_kernels.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <random>

#include "solver/fem/material_kernels.h"
#include "solver/fem/material_table.h"

namespace galsculpt::kernels {
namespace {

Eigen::Matrix3d toEigen(const M3& m) {
  return Eigen::Map<const Eigen::Matrix3d>(m.a);
}
M3 fromEigen(const Eigen::Matrix3d& m) {
  M3 out;
  for (int i = 0; i < 9; ++i) out.a[i] = m.data()[i];
  return out;
}

RestData restOf(const double p[12]) {
  RestData r;
  EXPECT_TRUE(computeRest(p, r));
  return r;
}

// A tet of no special shape and a soft material, for the kernels' tests.
constexpr double kSampleTet[12] = {0, 0, 0, 1, 0.1, 0, 0.2, 0.9, 0.1, 0.1, 0.2, 1.1};
constexpr Lame kSampleLame{3e4, 8e4};

// The 12x12 element Hessian (built from the modes' 12-vectors) equals D^T (dP/dF) D built from
// the 9x9 stress derivative, for each model, exact and projected.
TEST(ElementKernels, ElementHessianMatchesStressDerivative) {
  const double* rest = kSampleTet;
  const RestData r = restOf(rest);
  const Lame lame = kSampleLame;
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (const MaterialInfo& row : kMaterialModels) {  // every model of the table
    const MaterialModel model = row.model;
    for (Hessian mode : {Hessian::Exact, Hessian::ProjectedSpd}) {
      double x[12];
      for (int i = 0; i < 12; ++i) x[i] = rest[i] + u(gen);
      double energy, gradient[12], hessian[144], dpdf[81];
      evaluateElement(model, lame, r, x, kIntact, true, mode, energy, gradient, hessian);
      stressDerivative(model, lame, deformationGradient(r, x), mode == Hessian::ProjectedSpd, dpdf);
      double c[4][3];
      shapeGradients(r, c);
      Eigen::Matrix<double, 9, 12> d = Eigen::Matrix<double, 9, 12>::Zero();  // d vec F / d x
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) d(i + 3 * j, 3 * a + i) = c[a][j];
      const Eigen::Matrix<double, 12, 12> expected =
          r.volume * d.transpose() * Eigen::Map<Eigen::Matrix<double, 9, 9>>(dpdf) * d;
      const Eigen::Map<Eigen::Matrix<double, 12, 12>> got(hessian);
      EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
      EXPECT_EQ((got - got.transpose()).cwiseAbs().maxCoeff(), 0.0) << "exactly symmetric";
    }
  }
}

// The open cracks an evaluation reports (what the frame compares to keep a chord step): none on
// an intact element, every damaged edge where nothing is pressed or cracks cannot push back, and
// not a crack whose faces are pressed together (it carries load: another stiffness).
TEST(ElementKernels, EvaluationReportsWhichCracksAreOpen) {
  const double* rest = kSampleTet;
  const RestData r = restOf(rest);
  const Lame lame = kSampleLame;
  double stretched[12], squeezed[12];
  for (int i = 0; i < 12; ++i) stretched[i] = squeezed[i] = 1.1 * rest[i];
  for (int k = 0; k < 3; ++k) squeezed[3 + k] = 0.7 * rest[3 + k];  // edge 0-1 pressed shorter
  auto opened = [&](const double* x, std::uint8_t intact, bool resists) {
    double energy, gradient[12], hessian[144];
    std::uint8_t set = 0xff;
    evaluateElement(MaterialModel::StVK, lame, r, x, intact, resists, Hessian::Exact, energy,
                    gradient, hessian, &set);
    return set;
  };
  EXPECT_EQ(opened(squeezed, kIntact, true), 0);
  EXPECT_EQ(opened(stretched, 0x3e, true), 0x01);
  EXPECT_EQ(opened(stretched, 0x00, true), 0x3f) << "every crack open";
  EXPECT_EQ(opened(squeezed, 0x3e, false), 0x01) << "cracks that cannot push back";
  EXPECT_EQ(opened(squeezed, 0x3e, true), 0x00) << "pressed shut";
  EXPECT_EQ(opened(squeezed, 0x00, true) & 0x01, 0);
  // Two opposite intact edges (two pieces): only damaged edges are ever reported open.
  for (const std::uint8_t intact : {0x21, 0x12, 0x0c}) {
    const auto damaged = static_cast<std::uint8_t>(~intact & kIntact);
    EXPECT_EQ(opened(stretched, intact, true), damaged) << int(intact);
    EXPECT_EQ(opened(stretched, intact, false), damaged) << int(intact);
    EXPECT_EQ(opened(squeezed, intact, true) & intact, 0) << int(intact);
  }
}

// The knife leaves its cracks at rest: a tie between open and closed, which round-off must not
// decide (another executor's fused multiply-adds, a start moved by a last bit). Every crack at
// rest within round-off is open and its stiffness is that of exact rest; pressed shorter than
// round-off can explain, it closes (EvaluationReportsWhichCracksAreOpen).
TEST(ElementKernels, ACrackAtRestIsOpenWhateverItsRoundOff) {
  const double* rest = kSampleTet;
  const RestData r = restOf(rest);
  const Lame lame = kSampleLame;
  std::mt19937 gen(11);
  std::uniform_int_distribution<int> ulps(-8, 8);
  for (const std::uint8_t intact : {0x00, 0x3e, 0x21, 0x07}) {
    const auto damaged = static_cast<std::uint8_t>(~intact & kIntact);
    double exact[144], e0, g0[12];
    std::uint8_t set0 = 0;
    evaluateElement(MaterialModel::StVK, lame, r, rest, intact, true, Hessian::Exact, e0, g0, exact,
                    &set0);
    EXPECT_EQ(set0, damaged) << int(intact);
    double scale = 0.0;
    for (double v : exact) scale = std::max(scale, std::abs(v));
    for (int trial = 0; trial < 200; ++trial) {
      double x[12], energy, gradient[12], hessian[144];
      for (int i = 0; i < 12; ++i) x[i] = rest[i] + 1e-16 * ulps(gen);
      std::uint8_t set = 0;
      evaluateElement(MaterialModel::StVK, lame, r, x, intact, true, Hessian::Exact, energy,
                      gradient, hessian, &set);
      ASSERT_EQ(set, damaged) << "intact " << int(intact) << ", trial " << trial;
      for (int i = 0; i < 144; ++i)
        ASSERT_NEAR(hessian[i], exact[i], 1e-9 * scale) << "intact " << int(intact) << ", " << i;
    }
  }
}

TEST(ElementKernels, RestDataOfADegenerateTetIsRefused) {
  const double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  RestData r;
  EXPECT_FALSE(computeRest(flat, r));
  const double good[12] = {0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 3};
  ASSERT_TRUE(computeRest(good, r));
  EXPECT_DOUBLE_EQ(r.volume, 1.0);
  EXPECT_DOUBLE_EQ(r.restLengthSq[0], 4.0);
  EXPECT_DOUBLE_EQ(r.restLengthSq[5], 10.0);
}

// The opening problem's elimination: for every set of edges, the solution on the set, the
// right-hand side's remainder off it and the Schur complement, against Eigen's dense solves on
// a strain stiffness K (badly scaled on purpose: one edge a hundred times stiffer).
TEST(ElementKernels, EliminatingEdgesGivesTheSolutionTheRemainderAndTheSchurComplement) {
  std::mt19937 gen(5);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Matrix<double, 6, 6> root =
      Eigen::Matrix<double, 6, 6>::NullaryExpr([&] { return n(gen); });
  Eigen::Matrix<double, 6, 6> k =
      root * root.transpose() + 0.1 * Eigen::Matrix<double, 6, 6>::Identity();
  k.row(2) *= 10.0;
  k.col(2) *= 10.0;
  double kk[6][6], rhs[6];
  for (int r = 0; r < 6; ++r) {
    rhs[r] = n(gen);
    for (int c = 0; c < 6; ++c) kk[r][c] = k(r, c);
  }
  for (int set = 0; set < 64; ++set) {
    double h[6][6], b[6], c[6];
    eliminateEdges(kk, rhs, static_cast<std::uint8_t>(set), h, b, c);
    std::vector<int> in, out;
    for (int e = 0; e < 6; ++e) ((set >> e) & 1 ? in : out).push_back(e);
    const int ni = static_cast<int>(in.size()), no = static_cast<int>(out.size());
    Eigen::MatrixXd kss(ni, ni), kos(no, ni), koo(no, no);
    Eigen::VectorXd rs(ni), ro(no);
    for (int i = 0; i < ni; ++i) {
      rs[i] = rhs[in[i]];
      for (int j = 0; j < ni; ++j) kss(i, j) = k(in[i], in[j]);
      for (int j = 0; j < no; ++j) kos(j, i) = k(out[j], in[i]);
    }
    for (int i = 0; i < no; ++i) {
      ro[i] = rhs[out[i]];
      for (int j = 0; j < no; ++j) koo(i, j) = k(out[i], out[j]);
    }
    const Eigen::VectorXd cs = ni ? Eigen::VectorXd(kss.ldlt().solve(rs)) : Eigen::VectorXd();
    const Eigen::MatrixXd schur =
        ni ? Eigen::MatrixXd(koo - kos * kss.ldlt().solve(kos.transpose())) : koo;
    const double scale = k.cwiseAbs().maxCoeff();
    for (int i = 0; i < ni; ++i)
      EXPECT_NEAR(c[in[i]], cs[i], 1e-10 * cs.cwiseAbs().maxCoeff()) << set;
    for (int i = 0; i < no; ++i) {
      EXPECT_EQ(c[out[i]], 0.0) << set;
      const double remainder = ni ? ro[i] - (kos.row(i) * cs)(0) : ro[i];
      EXPECT_NEAR(b[out[i]], remainder, 1e-10 * scale * (1.0 + cs.cwiseAbs().sum())) << set;
      for (int j = i; j < no; ++j)
        EXPECT_NEAR(h[out[i]][out[j]], schur(i, j), 1e-10 * scale) << set;
    }
  }
}

// The CPU's copy of the elimination for each set (its loops unrolled, the set's tests decided
// at compile time) against the loop over a run-time set that the GPU runs: the same bits.
TEST(ElementKernels, EachSetsOwnEliminationGivesTheGenericLoopsBits) {
  std::mt19937 gen(8);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Matrix<double, 6, 6> root =
        Eigen::Matrix<double, 6, 6>::NullaryExpr([&] { return n(gen); });
    const Eigen::Matrix<double, 6, 6> k =
        root * root.transpose() + 0.1 * Eigen::Matrix<double, 6, 6>::Identity();
    double kk[6][6], rhs[6];
    for (int r = 0; r < 6; ++r) {
      rhs[r] = n(gen);
      for (int c = 0; c < 6; ++c) kk[r][c] = k(r, c);
    }
    for (int set = 0; set < 64; ++set) {
      double h1[6][6] = {}, b1[6], c1[6], h2[6][6] = {}, b2[6], c2[6];
      eliminateEdges(kk, rhs, static_cast<std::uint8_t>(set), h1, b1, c1);
      eliminateEdgesIn(static_cast<std::uint8_t>(set), kk, rhs, h2, b2, c2);
      EXPECT_EQ(std::memcmp(h1, h2, sizeof h1), 0) << set;
      EXPECT_EQ(std::memcmp(b1, b2, sizeof b1), 0) << set;
      EXPECT_EQ(std::memcmp(c1, c2, sizeof c1), 0) << set;
    }
  }
}

// The return lands on the yield surface and keeps det Fp = 1; a second return barely moves.
TEST(ElementKernels, PlasticReturnLandsOnTheYieldSurface) {
  const Lame lame{1e5, 2e5};
  const PlasticParamsData params{2000.0, 500.0};
  Eigen::Matrix3d f;
  f << 1.2, 0.1, 0.0, 0.05, 0.9, 0.02, 0.0, 0.03, 0.95;
  M3 fp = identity3();
  double strain = 0.0;
  ASSERT_TRUE(plasticReturn(lame, params, fromEigen(f), fp, strain));
  EXPECT_GT(strain, 0.0);
  EXPECT_NEAR(determinant(fp), 1.0, 1e-12);
  const Eigen::Matrix3d fe = f * toEigen(fp);
  // log of the singular values, from the eigenvalues of Fe^T Fe (log s = log(lambda) / 2).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(fe.transpose() * fe);
  const Eigen::Vector3d logs = 0.5 * eigen.eigenvalues().array().log();
  const double q = std::sqrt(1.5) * 2.0 * lame.mu * (logs.array() - logs.mean()).matrix().norm();
  EXPECT_NEAR(q, params.yieldStress + params.hardening * strain, 1e-6 * params.yieldStress);
  const double before = strain;
  plasticReturn(lame, params, fromEigen(f), fp, strain);
  EXPECT_NEAR(strain, before, 1e-12) << "on the surface: at most a round-off flow";
  // An inverted element flows by its continued logarithm (hencky_strain.h) where the model's
  // energy includes the flow, as that energy does: finite, volume-preserving, the element's
  // orientation kept. Under another model it does not flow.
  const M3 inverted = fromEigen(Eigen::Vector3d(1.5, 1.0, -0.5).asDiagonal());
  M3 fpInverted = identity3();
  double invertedStrain = 0.0;
  EXPECT_FALSE(plasticReturn(lame, params, inverted, fpInverted, invertedStrain));
  PlasticParamsData flowing = params;
  flowing.flowsCollapsed = true;
  EXPECT_TRUE(plasticReturn(lame, flowing, inverted, fpInverted, invertedStrain));
  EXPECT_GT(invertedStrain, 0.0);
  EXPECT_TRUE(toEigen(fpInverted).allFinite());
  EXPECT_NEAR(determinant(fpInverted), 1.0, 1e-12);
  EXPECT_LT(determinant(multiply(inverted, fpInverted)), 0.0);
}

}  // namespace
}  // namespace galsculpt::kernels
