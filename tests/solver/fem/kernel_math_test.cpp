// The 3x3 algebra of the shared kernels (solver/fem/kernel_math.h) against Eigen: products,
// inverses and determinants, the rotation-variant SVD and the symmetric eigen-solves on hard
// matrices, and the 6x6 inverse.
#include "solver/fem/kernel_math.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

namespace galsculpt::kernels {
namespace {

M3 fromEigen(const Eigen::Matrix3d& m) {
  M3 out;
  for (int i = 0; i < 9; ++i) out.a[i] = m.data()[i];
  return out;
}

Eigen::Matrix3d toEigen(const M3& m) {
  return Eigen::Map<const Eigen::Matrix3d>(m.a);
}

TEST(KernelMath, ProductsInversesAndDeterminantsAreEigens) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    Eigen::Matrix3d a, b;
    for (int i = 0; i < 9; ++i) a.data()[i] = u(rng), b.data()[i] = u(rng);
    a += 2.0 * Eigen::Matrix3d::Identity();
    EXPECT_LT((toEigen(multiply(fromEigen(a), fromEigen(b))) - a * b).norm(), 1e-14);
    EXPECT_EQ(toEigen(transpose(fromEigen(a))), a.transpose());
    EXPECT_NEAR(determinant(fromEigen(a)), a.determinant(), 1e-13);
    EXPECT_LT((toEigen(inverse(fromEigen(a))) - a.inverse()).norm(), 1e-12 * a.inverse().norm());
    EXPECT_NEAR(squaredNorm(fromEigen(a)), a.squaredNorm(), 1e-13);
    EXPECT_EQ(maxAbs(fromEigen(a)), a.cwiseAbs().maxCoeff());
  }
}

// Matrices that break naive SVDs: repeated, zero and negative singular values, huge ranges.
std::vector<Eigen::Matrix3d> hardMatrices() {
  std::mt19937 gen(7);
  std::normal_distribution<double> n(0.0, 1.0);
  auto rotation = [&] {
    Eigen::Quaterniond q(n(gen), n(gen), n(gen), n(gen));
    return q.normalized().toRotationMatrix();
  };
  std::vector<Eigen::Matrix3d> out;
  for (int i = 0; i < 200; ++i) out.push_back(Eigen::Matrix3d::NullaryExpr([&] { return n(gen); }));
  const Eigen::Vector3d diagonals[] = {
      {1, 1, 1},    {2, 2, 0.5},    {1, 1, -1},   {3, 0, 0},         {0, 0, 0},
      {1, 1e-9, 0}, {1e6, 1, 1e-6}, {-1, -1, -1}, {1, 1 + 1e-12, 1}, {5, -5, 1e-3}};
  for (const Eigen::Vector3d& d : diagonals) {
    out.push_back(d.asDiagonal());
    out.push_back(rotation() * d.asDiagonal() * rotation().transpose());
  }
  return out;
}

TEST(KernelMath, RotationVariantSvdReconstructsHardMatrices) {
  for (const Eigen::Matrix3d& f : hardMatrices()) {
    M3 u, v;
    double s[3];
    rotationVariantSvd(fromEigen(f), u, s, v);
    const Eigen::Matrix3d ue = toEigen(u), ve = toEigen(v);
    const double scale = std::max(f.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LT((ue * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal() * ve.transpose() - f)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-11 * scale)
        << f;
    EXPECT_LT((ue.transpose() * ue - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_LT((ve.transpose() * ve - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(ue.determinant(), 1.0, 1e-12);
    EXPECT_NEAR(ve.determinant(), 1.0, 1e-12);
    EXPECT_GE(s[0], std::abs(s[1]) - 1e-12 * scale);
    EXPECT_GE(s[1], std::abs(s[2]) - 1e-12 * scale);
    EXPECT_EQ(s[2] < -1e-12 * scale, f.determinant() < -1e-12 * scale * scale * scale) << f;
  }
}

TEST(KernelMath, ClosedFormEigenAgreesWithJacobiOrRefuses) {
  int accepted = 0;
  for (const Eigen::Matrix3d& m : hardMatrices()) {
    const Eigen::Matrix3d a = m.transpose() * m;
    double w[3], wj[3];
    M3 q, qj;
    symmetricEigen(fromEigen(a), wj, qj);
    const Eigen::Matrix3d qe = toEigen(qj);
    const double scale = std::max(a.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LT((qe * Eigen::Vector3d(wj[0], wj[1], wj[2]).asDiagonal() * qe.transpose() - a)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-13 * scale);
    if (!closedFormSymmetricEigen(fromEigen(a), w, q)) continue;
    ++accepted;
    std::sort(w, w + 3);
    std::sort(wj, wj + 3);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i], wj[i], 1e-10 * scale);
  }
  EXPECT_GT(accepted, 150) << "the closed form is the fast path: it must take most matrices";
}

TEST(KernelMath, Invert6MatchesEigenAndRefusesSingular) {
  std::mt19937 gen(5);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::NullaryExpr([&] { return n(gen); });
  double inv[36];
  ASSERT_TRUE(invert6(m.data(), inv));
  EXPECT_LT(
      (Eigen::Map<Eigen::Matrix<double, 6, 6>>(inv) * m - Eigen::Matrix<double, 6, 6>::Identity())
          .cwiseAbs()
          .maxCoeff(),
      1e-12);
  m.row(4) = m.row(2);
  m.col(1).setZero();
  EXPECT_FALSE(invert6(m.data(), inv));
}

}  // namespace
}  // namespace galsculpt::kernels
