#include "solver/frame/solver_options.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace galsculpt {
namespace {

TEST(SolverOptions, KeysAndLabelsAreUniqueAndEveryRowIsVisited) {
  std::set<std::string> keys, labels;
  int rows = 0;
  forEachSolverOption([&](const auto& f) {
    ++rows;
    EXPECT_TRUE(keys.insert(f.key).second) << f.key;
    EXPECT_TRUE(labels.insert(f.label).second) << f.label;
    EXPECT_NE(std::string(f.key), "preset") << "the preset chooses the columns; it is no row";
  });
  EXPECT_EQ(rows, 21);
}

// The struct's defaults are the converged column; each preset sets every row to its column.
TEST(SolverOptions, PresetsAreTheTablesColumns) {
  EXPECT_EQ(solverPreset(SolverPreset::Converged), SolverOptions{});
  const SolverOptions paper = solverPreset(SolverPreset::Paper);
  EXPECT_EQ(paper.preset, SolverPreset::Paper);
  int differing = 0;
  forEachSolverOption([&](const auto& f) {
    EXPECT_EQ(SolverOptions{}.*f.member, f.converged) << f.key;
    EXPECT_EQ(paper.*f.member, f.paper) << f.key;
    differing += !(f.converged == f.paper);
  });
  // The paper's one linearized step: one Newton iteration, one V-cycle, no chords, no local
  // iterations, no kept
  // stiffness, no predicted start, nothing held to a tolerance, CG on the coarsest level.
  EXPECT_EQ(paper.newtonIterations, 1);
  EXPECT_EQ(paper.pcgTolerance, 0.0);
  EXPECT_EQ(paper.coarseSolver, CoarseSolver::Cg);
  EXPECT_FALSE(paper.reuseStiffness);
  EXPECT_FALSE(paper.localNewton);
  EXPECT_FALSE(paper.predictedStart);
  EXPECT_FALSE(paper.acceleratedStart);
  EXPECT_FALSE(paper.convergePieces);
  EXPECT_EQ(paper.stiffnessTolerance, 0.0);
  EXPECT_EQ(differing, 9);
}

// Every number's preset values lie in the range a scene may give.
TEST(SolverOptions, PresetValuesAreWithinTheirRanges) {
  forEachSolverOption([&](const auto& f) {
    using T = std::decay_t<decltype(f.converged)>;
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      EXPECT_LE(f.min, f.max) << f.key;
      for (const T v : {f.converged, f.paper}) {
        EXPECT_GE(v, f.min) << f.key;
        EXPECT_LE(v, f.max) << f.key;
      }
    }
    if constexpr (std::is_same_v<T, std::string>) {
      if (f.check) {
        EXPECT_NO_THROW(f.check(f.converged)) << f.key;
      }
    }
  });
}

TEST(SolverOptions, EnumNamesRoundTrip) {
  auto roundTrip = [](auto value) {
    using E = decltype(value);
    for (const EnumName<E>& n : namesOf(value)) {
      EXPECT_EQ(enumFromName<E>(n.name), n.value) << n.name;
      EXPECT_STREQ(enumName(n.value), n.name);
    }
    EXPECT_FALSE(enumFromName<E>("no such name").has_value());
  };
  roundTrip(SolverType{});
  roundTrip(SolverPreset{});
  roundTrip(Smoother{});
  roundTrip(CoarseSolver{});
  roundTrip(EnergyGuard{});
  roundTrip(BackendRequest{});
  EXPECT_STREQ(enumName(Smoother::GaussSeidel), "gauss_seidel");
  EXPECT_EQ(enumFromName<BackendRequest>("cuda"), BackendRequest::Cuda);
}

TEST(SolverOptions, GridCheckRefusesMalformedSetups) {
  EXPECT_NO_THROW(checkGridSetup("50/1000/all"));
  EXPECT_THROW(checkGridSetup("50"), std::invalid_argument);
  EXPECT_THROW(checkGridSetup("1000/50/all"), std::invalid_argument);
  EXPECT_THROW(checkGridSetup("x/all"), std::invalid_argument);
}

// The converged preset: Newton to the residual tolerance, each step by CG preconditioned with
// a V-cycle, a direct coarsest level, chords and kept stiffnesses.
TEST(SolverOptions, ConvergedPresetsStepSettings) {
  const StepSettings s = stepSettings(SolverOptions{}, 0.01, 2);
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_EQ(s.substeps, 2);
  EXPECT_TRUE(s.multigrid);
  EXPECT_EQ(s.gridHandles, std::vector<int>{50});
  EXPECT_EQ(s.newtonIterations, 40);
  EXPECT_EQ(s.residualTolerance, 1e-2);
  EXPECT_TRUE(s.reuseStiffness);
  EXPECT_TRUE(s.predictedStart);
  EXPECT_TRUE(s.acceleratedStart);
  EXPECT_TRUE(s.convergePieces);
  EXPECT_FALSE(s.vertexGuard);
  EXPECT_EQ(s.stiffnessTolerance, 1e-3);
  EXPECT_FALSE(s.lineSearch);
  const MultigridSettings& mg = s.multigridSettings;
  EXPECT_TRUE(mg.pcg);
  EXPECT_EQ(mg.pcgTolerance, 1e-2);
  EXPECT_TRUE(mg.coarseCholesky);
  EXPECT_EQ(mg.preSweeps, 3);
  EXPECT_EQ(mg.postSweeps, 3);
  EXPECT_FALSE(mg.jacobi);
  EXPECT_TRUE(mg.jacobiOnDevice);
  EXPECT_EQ(mg.coarseIterations, 20);
  EXPECT_TRUE(mg.splitAggregates);
}

TEST(SolverOptions, EachOptionReachesItsSetting) {
  SolverOptions o = solverPreset(SolverPreset::Paper);
  o.grid = "20/300/all";
  o.fineSweeps = 5;
  o.coarseIterations = 7;
  o.smoother = Smoother::Jacobi;
  o.cycles = 3;
  o.frameBudgetMs = 12.0;
  o.energyGuard = EnergyGuard::Vertex;
  o.splitAggregates = false;
  const StepSettings s = stepSettings(o, 1.0 / 60.0, 1);
  EXPECT_EQ(s.gridHandles, (std::vector<int>{300, 20}));
  EXPECT_EQ(s.newtonIterations, 1);
  EXPECT_EQ(s.frameBudgetMs, 12.0);
  EXPECT_TRUE(s.vertexGuard);
  EXPECT_FALSE(s.predictedStart);
  EXPECT_FALSE(s.acceleratedStart);
  const MultigridSettings& mg = s.multigridSettings;
  EXPECT_EQ(mg.preSweeps, 5);
  EXPECT_EQ(mg.postSweeps, 5);
  EXPECT_EQ(mg.coarseIterations, 7);
  EXPECT_TRUE(mg.jacobi);
  EXPECT_FALSE(mg.jacobiOnDevice);
  EXPECT_FALSE(mg.pcg) << "pcg_tolerance 0: the V-cycles are the solve";
  EXPECT_FALSE(mg.coarseCholesky);
  EXPECT_EQ(mg.cycles, 3);
  EXPECT_FALSE(mg.splitAggregates);
  o.smoother = Smoother::GaussSeidel;
  EXPECT_FALSE(stepSettings(o, 1.0 / 60.0, 1).multigridSettings.jacobiOnDevice);
}

// The reference: Newton with line search and a direct solve to Newton's step test, whatever
// the multigrid's options; the start options stay, so it solves the same equations.
TEST(SolverOptions, ReferenceTypeGivesTheReferenceSettings) {
  SolverOptions o;
  o.type = SolverType::Reference;
  o.predictedStart = false;
  o.energyGuard = EnergyGuard::Vertex;
  const StepSettings s = stepSettings(o, 1.0 / 60.0, 1);
  EXPECT_FALSE(s.multigrid);
  EXPECT_TRUE(s.lineSearch);
  EXPECT_EQ(s.residualTolerance, 0.0);
  EXPECT_EQ(s.newtonIterations, 50);
  EXPECT_FALSE(s.vertexGuard);
  EXPECT_FALSE(s.reuseStiffness);
  EXPECT_EQ(s.stiffnessTolerance, 0.0);
  EXPECT_FALSE(s.predictedStart);
  EXPECT_TRUE(s.convergePieces);
  StepSettings base = stepSettings(SolverOptions{}, 1.0 / 60.0, 1);
  base.predictedStart = false;
  const StepSettings viaFunction = referenceSettings(base);
  EXPECT_EQ(s.tolerance, viaFunction.tolerance);
  EXPECT_EQ(s.newtonIterations, viaFunction.newtonIterations);
}

}  // namespace
}  // namespace galsculpt
