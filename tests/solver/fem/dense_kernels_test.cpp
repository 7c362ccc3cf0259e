// The small dense kernels of the multigrid's Galerkin products against Eigen.
#include "solver/fem/dense_kernels.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

namespace galsculpt {
namespace {

// (yr yc^T) kron A for each block of a row, summed: what a Galerkin product of affine modes
// adds for one fine row. The two steps against Eigen's products, to round-off.
TEST(DenseKernels, AffineModeProductsOfARowMatchTheKroneckerSum) {
  std::mt19937 gen(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int blocks = 1 + trial % 7;
    Eigen::Vector4d yr;
    for (int i = 0; i < 4; ++i) yr[i] = n(gen);
    Eigen::Matrix<double, 12, 12> want = Eigen::Matrix<double, 12, 12>::Zero();
    std::vector<double> twoStep(144, 0.0), row(36, 0.0);
    for (int b = 0; b < blocks; ++b) {
      Eigen::Vector4d yc;
      for (int i = 0; i < 4; ++i) yc[i] = n(gen);
      Eigen::Matrix3d a;
      for (int i = 0; i < 9; ++i) a(i % 3, i / 3) = n(gen);
      const Eigen::Matrix4d m = yr * yc.transpose();
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) want.block<3, 3>(3 * i, 3 * j) += m(i, j) * a;
      addBlockTimesModes(yc.data(), a.data(), row.data());
    }
    addModesTimesRow(yr.data(), row.data(), twoStep.data());
    const double scale = want.cwiseAbs().maxCoeff();
    for (int i = 0; i < 144; ++i) {
      EXPECT_NEAR(twoStep[i], want.data()[i], 1e-14 * scale) << i;
    }
  }
}

// T_r^T (sum over a row's blocks of B_c T_c) for 12x12 blocks, in two steps, against Eigen; and
// one block's triple product against the same.
TEST(DenseKernels, CoarseProductsOfARowMatchTheTripleProducts) {
  using M12 = Eigen::Matrix<double, 12, 12>;
  std::mt19937 gen(5);
  std::normal_distribution<double> n(0.0, 1.0);
  auto random = [&] {
    M12 m;
    for (int i = 0; i < 144; ++i) m.data()[i] = n(gen);
    return m;
  };
  for (int trial = 0; trial < 10; ++trial) {
    const int blocks = 1 + trial % 5;
    const M12 tr = random();
    M12 want = M12::Zero(), sum = M12::Zero(), twoStep = M12::Zero(), single = M12::Zero();
    for (int b = 0; b < blocks; ++b) {
      const M12 bc = random(), tc = random();
      want += tr.transpose() * bc * tc;
      addProduct12(bc.data(), tc.data(), sum.data());
      if (b == 0) {
        addTripleProduct12(tr.data(), bc.data(), tc.data(), single.data());
        EXPECT_LT((single - want).norm(), 1e-13 * want.norm());
      }
    }
    addTransposedProduct12(tr.data(), sum.data(), twoStep.data());
    EXPECT_LT((twoStep - want).norm(), 1e-13 * want.norm()) << blocks << " blocks";
  }
}

}  // namespace
}  // namespace galsculpt
