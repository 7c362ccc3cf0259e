// The solver's options, one row each, with the two presets' values beside them: the table that
// drives the struct below, its presets (solverPreset), the scene reader and writer
// (engine/scene), the command line's --solver-option, the Scene panel and the check of
// docs/scenes.md (tests/engine/scene/scene_test.cpp). stepSettings turns a set of options into
// the frame's numerical settings, the one place where the two meet.
//
// Adding an option: its row below (type, member, scene key, panel label, the `converged` and
// `paper` presets' values, the range a scene may give, a check or nullptr), its row in
// docs/scenes.md, and what it sets in stepSettings (solver_options.cpp). An option of a new
// enum type also needs the enum's names (namesOf below).
#pragma once

#include <optional>
#include <span>
#include <string>

#include "solver/frame/step.h"

namespace galsculpt {

// The solver's choices, parsed once from their names; nothing compares names after loading.
enum class SolverType { Multigrid, Reference };
// The multigrid's defaults: `converged` (Newton with multigrid-preconditioned CG until the
// residual is within tolerance) or `paper` (the paper's one linearized step, one V-cycle).
enum class SolverPreset { Converged, Paper };
// Auto: Gauss-Seidel on the CPU, Jacobi on a GPU (MultigridSettings::jacobiOnDevice).
enum class Smoother { Auto, GaussSeidel, Jacobi };
enum class CoarseSolver { Cg, Cholesky };
// What a Newton step that raised the potential shortens first (StepSettings::vertexGuard).
enum class EnergyGuard { Vertex, Body };
enum class BackendRequest { Auto, Cpu, Cuda };

// The grid setup's check: throws std::invalid_argument for a malformed one ("50/1000/all").
void checkGridSetup(const std::string& grid);

// X(type, member, key, label, converged, paper, min, max, check): the scene key ("solver":
// {KEY: ...}, --solver-option KEY=VALUE), the Scene panel's label, each preset's value, the
// range of a number, and a check of the value (throws std::invalid_argument) or nullptr.
#define GALSCULPT_SOLVER_OPTIONS(X)                                                                \
  X(SolverType, type, "type", "solver", SolverType::Multigrid, SolverType::Multigrid, 0, 0,        \
    nullptr)                                                                                       \
  X(std::string, grid, "grid", "grid (e.g. 50/1000/all)", "50/all", "50/all", 0, 0,                \
    checkGridSetup)                                                                                \
  X(int, fineSweeps, "fine_sweeps", "fine sweeps", 3, 3, 0, 10000, nullptr)                        \
  X(int, coarseIterations, "coarse_iters", "coarse iterations", 20, 20, 0, 100000, nullptr)        \
  X(Smoother, smoother, "smoother", "smoother", Smoother::Auto, Smoother::Auto, 0, 0, nullptr)     \
  X(CoarseSolver, coarseSolver, "coarse_solver", "coarse solver", CoarseSolver::Cholesky,          \
    CoarseSolver::Cg, 0, 0, nullptr)                                                               \
  X(int, newtonIterations, "newton_iters", "Newton iterations (most)", 40, 1, 1, 100, nullptr)     \
  X(int, cycles, "cycles", "V-cycles per solve", 1, 1, 1, 1000, nullptr)                           \
  X(double, pcgTolerance, "pcg_tolerance", "PCG tolerance (0: no CG)", 1e-2, 0.0, 0.0, 0.5,        \
    nullptr)                                                                                       \
  X(double, residualTolerance, "residual_tolerance", "residual tolerance", 1e-2, 1e-2, 1e-12,      \
    10.0, nullptr)                                                                                 \
  X(double, frameBudgetMs, "frame_budget_ms", "frame budget (ms, 0: none)", 0.0, 0.0, 0.0, 1e6,    \
    nullptr)                                                                                       \
  X(bool, reuseStiffness, "reuse_stiffness", "chord steps", true, false, 0, 0, nullptr)            \
  X(int, lbfgsPairs, "lbfgs_pairs", "L-BFGS pairs (0: none)", 0, 0, 0, 8, nullptr)                 \
  X(bool, localNewton, "local_newton", "solve where the residual is", true, false, 0, 0, nullptr)  \
  X(bool, predictedStart, "predicted_start", "predicted start", true, false, 0, 0, nullptr)        \
  X(bool, acceleratedStart, "accelerated_start", "accelerated start", true, false, 0, 0, nullptr)  \
  X(bool, convergePieces, "converge_pieces", "converge every piece", true, false, 0, 0, nullptr)   \
  X(EnergyGuard, energyGuard, "energy_guard", "energy guard", EnergyGuard::Body,                   \
    EnergyGuard::Body, 0, 0, nullptr)                                                              \
  X(double, stiffnessTolerance, "stiffness_tolerance", "stiffness tolerance", 1e-3, 0.0, 0.0, 0.1, \
    nullptr)                                                                                       \
  X(BackendRequest, backend, "backend", "backend", BackendRequest::Auto, BackendRequest::Auto, 0,  \
    0, nullptr)                                                                                    \
  X(bool, splitAggregates, "split_aggregates", "crack-aware coarse levels", true, true, 0, 0,      \
    nullptr)

// Defaults are the converged preset's; `preset` says which preset the others started from.
struct SolverOptions {
  SolverPreset preset = SolverPreset::Converged;
#define GALSCULPT_OPTION_MEMBER(T, member, key, label, converged, paper, lo, hi, check) \
  T member = converged;
  GALSCULPT_SOLVER_OPTIONS(GALSCULPT_OPTION_MEMBER)
#undef GALSCULPT_OPTION_MEMBER

  bool operator==(const SolverOptions&) const = default;
};

// One row of the table, typed.
template <typename T>
struct OptionField {
  const char* key;
  const char* label;
  T SolverOptions::*member;
  T converged, paper;
  double min, max;  // numbers only
  void (*check)(const std::string&);
  const T& presetValue(SolverPreset p) const {
    return p == SolverPreset::Paper ? paper : converged;
  }
};

// f(OptionField<T>{...}) for every row, in table order.
template <typename F>
void forEachSolverOption(F&& f) {
#define GALSCULPT_OPTION_VISIT(T, member, key, label, converged, paper, lo, hi, check) \
  f(OptionField<T>{key, label, &SolverOptions::member, T(converged), T(paper), lo, hi, check});
  GALSCULPT_SOLVER_OPTIONS(GALSCULPT_OPTION_VISIT)
#undef GALSCULPT_OPTION_VISIT
}

// The options a preset stands for (keys a scene gives override them).
SolverOptions solverPreset(SolverPreset preset);

// The frame's numerical settings for `options` at time step `dt` in `substeps` sub-steps; a
// `reference` type gives the reference solver's (referenceSettings: Newton with line search and
// a direct solve), which keeps only the start options (predicted, accelerated, pieces).
StepSettings stepSettings(const SolverOptions& options, double dt, int substeps);

// An enum value and its name as written in scenes, on the command line and in the panel.
template <typename E>
struct EnumName {
  E value;
  const char* name;
};
std::span<const EnumName<SolverType>> namesOf(SolverType);
std::span<const EnumName<SolverPreset>> namesOf(SolverPreset);
std::span<const EnumName<Smoother>> namesOf(Smoother);
std::span<const EnumName<CoarseSolver>> namesOf(CoarseSolver);
std::span<const EnumName<EnergyGuard>> namesOf(EnergyGuard);
std::span<const EnumName<BackendRequest>> namesOf(BackendRequest);

// Whether namesOf(E{}) exists: the option types that are enums of the table.
template <typename E>
concept NamedEnum = requires(E e) {
  namesOf(e);
};

template <NamedEnum E>
const char* enumName(E value) {
  for (const EnumName<E>& n : namesOf(value))
    if (n.value == value) return n.name;
  return "?";
}
template <NamedEnum E>
std::optional<E> enumFromName(const std::string& name) {
  for (const EnumName<E>& n : namesOf(E{}))
    if (name == n.name) return n.value;
  return std::nullopt;
}

}  // namespace galsculpt
