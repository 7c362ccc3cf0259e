#include "solver/frame/direct_solver.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <vector>

#include "solver/frame/step.h"
#include "solver/model/sim_model.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

// M / h^2 + K of a twisted bar: symmetric positive definite, on the model's block pattern.
struct BarSystem {
  SimModel model =
      buildSimModel(test::gridBar(3, 6, 2, 0.05),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e6, 0.4), 1000.0, {}});
  BlockSparseMatrix a{model.pattern};
  std::vector<double> blocks;
  BarSystem() {
    SimState state = initialState(model);
    for (int v = 0; v < model.numVertices(); ++v) {
      const Vec3 p = model.mesh.vertices[v];
      state.x[v] += 0.02 * Vec3(std::sin(9 * p.y()), 0.0, std::cos(7 * p.y()));
    }
    Eigen::VectorXd g;
    assembleElastic(model, state.x, state, g, &a);
    for (int v = 0; v < model.numVertices(); ++v)
      a.blocks[model.pattern.diagonal[v]] += model.mass[v] * 3600.0 * Eigen::Matrix3d::Identity();
    for (const Eigen::Matrix3d& b : a.blocks) blocks.insert(blocks.end(), b.data(), b.data() + 9);
  }
};

TEST(DirectSolver, SolvesAsEigensCholeskyDoes) {
  BarSystem s;
  const int n = 3 * s.model.numVertices();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  DirectSolver solver(s.model.pattern);
  ASSERT_TRUE(solver.solve(s.blocks.data(), b.data(), x.data()));
  const Eigen::SparseMatrix<double> a = s.a.toEigen();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> eigen(a);
  const Eigen::VectorXd expected = eigen.solve(b);
  EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm());
  EXPECT_LT((a * x - b).norm(), 1e-10 * b.norm());
  // The pattern is analysed once; a second solve with other values factors them anew.
  for (double& v : s.blocks) v *= 2.0;
  ASSERT_TRUE(solver.solve(s.blocks.data(), b.data(), x.data()));
  EXPECT_LT((x - 0.5 * expected).norm(), 1e-10 * expected.norm());
}

TEST(DirectSolver, RefusesAMatrixThatIsNotPositiveDefinite) {
  BarSystem s;
  for (double& v : s.blocks) v = -v;
  const int n = 3 * s.model.numVertices();
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 7.0);
  DirectSolver solver(s.model.pattern);
  EXPECT_FALSE(solver.solve(s.blocks.data(), b.data(), x.data()));
  EXPECT_TRUE((x.array() == 7.0).all()) << "x is left as it was";
}

}  // namespace
}  // namespace galsculpt
