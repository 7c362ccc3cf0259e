// The matrices and the cycle the multigrid's tests share: the backward-Euler matrix of a
// deformed, hanging bar, and the hierarchy's solve on it on the CPU executor.
#pragma once

#include <cmath>
#include <vector>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/step.h"
#include "solver/model/sim_model.h"
#include "solver/multigrid/multigrid.h"
#include "solver/multigrid/multigrid_cycle.h"
#include "solver/multigrid/multigrid_layout.h"
#include "tests/test_util.h"

namespace galsculpt::test {

// The backward-Euler matrix M/h^2 + K of a deformed, hanging bar.
struct System {
  SimModel model;
  BlockSparseMatrix a;
  Eigen::VectorXd b;
};

inline System elasticitySystem(int nx = 3, int ny = 12, int nz = 3) {
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
  // The paper's V-cycle: Gauss-Seidel, CG on the coarsest level.
  static MultigridCycle<CpuExecutor>::Settings settings(int cycles = 1) {
    MultigridCycle<CpuExecutor>::Settings st = solverPreset(SolverPreset::Paper);
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

}  // namespace galsculpt::test
