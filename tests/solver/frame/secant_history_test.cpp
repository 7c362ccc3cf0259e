// L-BFGS's two-loop recursion (secant_history.h) against BFGS's inverse update written out as
// dense matrices: H_{k+1} = (I - rho s y^T) H_k (I - rho y s^T) + rho s s^T from H_0.
#include "solver/frame/secant_history.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "solver/frame/cpu_executor.h"

namespace galsculpt {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kDofs = 9;

MatrixXd randomSpd(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixXd a(kDofs, kDofs);
  for (int i = 0; i < a.size(); ++i) a.data()[i] = u(rng);
  return a * a.transpose() + kDofs * MatrixXd::Identity(kDofs, kDofs);
}

VectorXd randomVector(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VectorXd v(kDofs);
  for (int i = 0; i < kDofs; ++i) v[i] = u(rng);
  return v;
}

// The inverse BFGS's updates of h0Inverse make from the pairs (x_{k+1} - x_k, g_{k+1} - g_k)
// of `points`, skipping pairs without positive curvature.
MatrixXd bfgsInverse(const MatrixXd& h0Inverse, const std::vector<VectorXd>& xs,
                     const std::vector<VectorXd>& gs, size_t firstPair) {
  MatrixXd h = h0Inverse;
  const MatrixXd id = MatrixXd::Identity(kDofs, kDofs);
  for (size_t k = firstPair; k + 1 < xs.size(); ++k) {
    const VectorXd s = xs[k + 1] - xs[k], y = gs[k + 1] - gs[k];
    const double sy = s.dot(y);
    if (!(sy > 0.0)) continue;
    const double rho = 1.0 / sy;
    h = (id - rho * s * y.transpose()) * h * (id - rho * y * s.transpose()) +
        rho * s * s.transpose();
  }
  return h;
}

// The recursion's step for b, H0^-1 applied by a dense solve between the loops.
VectorXd twoLoop(SecantHistory<CpuExecutor>& history, const MatrixXd& h0, const VectorXd& b) {
  VectorXd q = b;
  history.firstLoop(q.data());
  VectorXd z = h0.ldlt().solve(q);
  history.secondLoop(z.data());
  return z;
}

// Points on a quadratic-plus-quartic gradient, so the pairs' curvatures differ.
VectorXd gradientAt(const MatrixXd& a, const VectorXd& x) {
  return a * x + x.cwiseProduct(x).cwiseProduct(x);
}

TEST(SecantHistory, TheTwoLoopRecursionIsBfgsInverseUpdate) {
  std::mt19937 rng(7);
  CpuExecutor ex;
  const MatrixXd a = randomSpd(rng), h0 = randomSpd(rng);
  SecantHistory<CpuExecutor> history(ex, kDofs, 5);
  std::vector<VectorXd> xs, gs;
  for (int k = 0; k < 4; ++k) {
    xs.push_back(randomVector(rng));
    gs.push_back(gradientAt(a, xs.back()));
    history.record(xs.back().data(), gs.back().data());
  }
  EXPECT_EQ(history.pairs(), 3);
  const VectorXd b = randomVector(rng);
  const VectorXd expected = bfgsInverse(h0.inverse(), xs, gs, 0) * b;
  const VectorXd got = twoLoop(history, h0, b);
  EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm());
  // Each pair's secant equation holds for the newest: H y = s.
  const VectorXd y = gs[3] - gs[2], s = xs[3] - xs[2];
  EXPECT_LT((twoLoop(history, h0, y) - s).norm(), 1e-12 * s.norm());
}

TEST(SecantHistory, APairWithoutPositiveCurvatureChangesNothing) {
  std::mt19937 rng(11);
  CpuExecutor ex;
  const MatrixXd h0 = randomSpd(rng);
  SecantHistory<CpuExecutor> history(ex, kDofs, 4);
  const VectorXd x0 = randomVector(rng), x1 = randomVector(rng);
  const VectorXd g0 = randomVector(rng);
  const VectorXd g1 = g0 - (x1 - x0);  // s.y = -|s|^2 < 0: the potential curves down
  history.record(x0.data(), g0.data());
  history.record(x1.data(), g1.data());
  EXPECT_EQ(history.pairs(), 1);
  const VectorXd b = randomVector(rng);
  const VectorXd plain = h0.ldlt().solve(b);
  EXPECT_LT((twoLoop(history, h0, b) - plain).norm(), 1e-14 * plain.norm());
}

TEST(SecantHistory, KeepsTheNewestPairsAndForgetsOnClear) {
  std::mt19937 rng(3);
  CpuExecutor ex;
  const MatrixXd a = randomSpd(rng), h0 = randomSpd(rng);
  const int capacity = 2;
  SecantHistory<CpuExecutor> history(ex, kDofs, capacity);
  std::vector<VectorXd> xs, gs;
  for (int k = 0; k < 6; ++k) {
    xs.push_back(randomVector(rng));
    gs.push_back(gradientAt(a, xs.back()));
    history.record(xs.back().data(), gs.back().data());
  }
  EXPECT_EQ(history.pairs(), capacity);
  EXPECT_EQ(history.recorded(), 5);
  const VectorXd b = randomVector(rng);
  const VectorXd expected = bfgsInverse(h0.inverse(), xs, gs, xs.size() - 1 - capacity) * b;
  EXPECT_LT((twoLoop(history, h0, b) - expected).norm(), 1e-12 * expected.norm());

  history.clear();
  EXPECT_EQ(history.pairs(), 0);
  history.record(xs[0].data(), gs[0].data());  // a first point again: no pair yet
  EXPECT_EQ(history.pairs(), 0);
  const VectorXd plain = h0.ldlt().solve(b);
  EXPECT_LT((twoLoop(history, h0, b) - plain).norm(), 1e-14 * plain.norm());
}

}  // namespace
}  // namespace galsculpt
