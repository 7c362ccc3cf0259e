#include "solver/model/solver_options.h"

#include "solver/frame/step.h"

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
  EXPECT_EQ(rows, 20);
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

// The frame reads the options themselves: stepSettings keeps every row as given (the converged
// and paper presets, and a set with every kind of row changed) and adds what follows from them.
TEST(SolverOptions, StepSettingsAreTheOptionsThemselves) {
  SolverOptions changed = solverPreset(SolverPreset::Paper);
  changed.grid = "20/300/all";
  changed.fineSweeps = 5;
  changed.coarseIterations = 7;
  changed.smoother = Smoother::Jacobi;
  changed.cycles = 3;
  changed.frameBudgetMs = 12.0;
  changed.energyGuard = EnergyGuard::Vertex;
  changed.splitAggregates = false;
  for (const SolverOptions& o :
       {solverPreset(SolverPreset::Converged), solverPreset(SolverPreset::Paper), changed}) {
    const StepSettings s = stepSettings(o, 0.01, 2);
    EXPECT_EQ(static_cast<const SolverOptions&>(s), o);
    EXPECT_EQ(s.dt, 0.01);
    EXPECT_EQ(s.substeps, 2);
    EXPECT_TRUE(s.multigrid());
    EXPECT_EQ(s.gridHandles, parseGridSetup(o.grid));
    EXPECT_EQ(s.pcg(), o.pcgTolerance > 0.0);
    EXPECT_EQ(s.vertexGuard(), o.energyGuard == EnergyGuard::Vertex);
    EXPECT_FALSE(s.lineSearch);
  }
  EXPECT_EQ(stepSettings(changed, 0.01, 1).gridHandles, (std::vector<int>{300, 20}));
  EXPECT_TRUE(stepSettings(SolverOptions{}, 0.01, 1).pcg()) << "the converged preset runs PCG";
  EXPECT_FALSE(stepSettings(changed, 0.01, 1).pcg()) << "pcg_tolerance 0: V-cycles are the solve";
}

// StepSettings{} is the paper's one linearized step with a direct solve.
TEST(SolverOptions, DefaultStepSettingsAreThePapersStepSolvedDirectly) {
  const StepSettings s;
  EXPECT_FALSE(s.multigrid());
  EXPECT_EQ(s.newtonIterations, 1);
  EXPECT_FALSE(s.lineSearch);
  EXPECT_FALSE(s.pcg());
  EXPECT_FALSE(s.predictedStart);
  EXPECT_FALSE(s.reuseStiffness);
  EXPECT_EQ(s.coarseSolver, CoarseSolver::Cg);
  EXPECT_EQ(s.fineSweeps, 3);
}

// The reference: Newton with line search and a direct solve to Newton's step test, whatever
// the multigrid's options; the start options stay, so it solves the same equations.
TEST(SolverOptions, ReferenceTypeGivesTheReferenceSettings) {
  SolverOptions o;
  o.type = SolverType::Reference;
  o.predictedStart = false;
  o.energyGuard = EnergyGuard::Vertex;
  const StepSettings s = stepSettings(o, 1.0 / 60.0, 1);
  EXPECT_FALSE(s.multigrid());
  EXPECT_TRUE(s.lineSearch);
  EXPECT_EQ(s.residualTolerance, 0.0);
  EXPECT_EQ(s.newtonIterations, 400);
  EXPECT_FALSE(s.vertexGuard());
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
