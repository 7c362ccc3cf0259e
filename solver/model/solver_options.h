// The solver's options, one row each, with the two presets' values beside them: the table that
// drives the struct below, its presets (solverPreset), the scene reader and writer
// (engine/scene), the command line's --solver-option, the Scene panel and the check of
// docs/scenes.md (tests/engine/scene/scene_test.cpp). The frame and the multigrid read the
// struct itself: StepSettings (solver/frame/step.h) is a SolverOptions with the frame's
// numerical constants beside it, so an option is its row and nothing copies it.
// (It lives with the model, as MuJoCo's mjOption lives in mjModel: the multigrid below the frame
// reads it too.)
//
// Adding an option: its row below (type, member, scene key, panel label, the `converged` and
// `paper` presets' values, the range a scene may give, a check or nullptr), its row in
// docs/scenes.md, and the code that reads it. An option of a new enum type also needs the enum's
// names (namesOf below).
#pragma once

#include <optional>
#include <version>
#if __cplusplus >= 202002L
#include <span>
#endif
#include <string>
#include <vector>

namespace galsculpt {

// The solver's choices, parsed once from their names; nothing compares names after loading.
enum class SolverType { Multigrid, Reference };
// The multigrid's defaults: `converged` (Newton with multigrid-preconditioned CG until the
// residual is within tolerance) or `paper` (the paper's one linearized step, one V-cycle).
enum class SolverPreset { Converged, Paper };
// Auto: Gauss-Seidel, except on a device where the V-cycle preconditions CG (multigrid_cycle.h).
enum class Smoother { Auto, GaussSeidel, Jacobi };
enum class CoarseSolver { Cg, Cholesky };
// What a Newton step that raised the potential shortens first (line_search.h).
enum class EnergyGuard { Vertex, Body };
// DeviceLike: the CUDA backend's paths on the CPU (solver/frame/device_like_backend.h), for
// the device's launch and synchronization counts on any machine.
enum class BackendRequest { Auto, Cpu, Cuda, DeviceLike };

// "50/1000/all" -> {1000, 50}: handle counts from the finest coarse level down. Throws
// std::invalid_argument on a malformed setup.
std::vector<int> parseGridSetup(const std::string& grid);
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

#if __cplusplus >= 202002L  // (CUDA sources compile as C++17: the frame reads the struct only)
  bool operator==(const SolverOptions&) const = default;
#endif
};

// One row of the table, typed.
template <typename T>
struct OptionField {
  const char* key;
  const char* label;
  using Member = T SolverOptions::*;
  Member member;
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

#if __cplusplus >= 202002L  // (the names are the host's: scenes, the command line, the panel)
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
#endif

}  // namespace galsculpt
