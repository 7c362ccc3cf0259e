#include "solver/frame/solver_options.h"

#include "solver/multigrid/multigrid.h"

namespace galsculpt {

namespace {

constexpr EnumName<SolverType> kSolverTypeNames[] = {{SolverType::Multigrid, "multigrid"},
                                                     {SolverType::Reference, "reference"}};
constexpr EnumName<SolverPreset> kSolverPresetNames[] = {{SolverPreset::Converged, "converged"},
                                                         {SolverPreset::Paper, "paper"}};
constexpr EnumName<Smoother> kSmootherNames[] = {{Smoother::Auto, "auto"},
                                                 {Smoother::GaussSeidel, "gauss_seidel"},
                                                 {Smoother::Jacobi, "jacobi"}};
constexpr EnumName<CoarseSolver> kCoarseSolverNames[] = {{CoarseSolver::Cg, "cg"},
                                                         {CoarseSolver::Cholesky, "cholesky"}};
constexpr EnumName<EnergyGuard> kEnergyGuardNames[] = {{EnergyGuard::Vertex, "vertex"},
                                                       {EnergyGuard::Body, "body"}};
constexpr EnumName<BackendRequest> kBackendNames[] = {
    {BackendRequest::Auto, "auto"}, {BackendRequest::Cpu, "cpu"}, {BackendRequest::Cuda, "cuda"}};

}  // namespace

std::span<const EnumName<SolverType>> namesOf(SolverType) {
  return kSolverTypeNames;
}
std::span<const EnumName<SolverPreset>> namesOf(SolverPreset) {
  return kSolverPresetNames;
}
std::span<const EnumName<Smoother>> namesOf(Smoother) {
  return kSmootherNames;
}
std::span<const EnumName<CoarseSolver>> namesOf(CoarseSolver) {
  return kCoarseSolverNames;
}
std::span<const EnumName<EnergyGuard>> namesOf(EnergyGuard) {
  return kEnergyGuardNames;
}
std::span<const EnumName<BackendRequest>> namesOf(BackendRequest) {
  return kBackendNames;
}

void checkGridSetup(const std::string& grid) {
  parseGridSetup(grid);
}

SolverOptions solverPreset(SolverPreset preset) {
  SolverOptions o;
  o.preset = preset;
  forEachSolverOption([&](const auto& field) { o.*field.member = field.presetValue(preset); });
  return o;
}

StepSettings stepSettings(const SolverOptions& o, double dt, int substeps) {
  StepSettings s;
  s.dt = dt;
  s.substeps = substeps;
  s.newtonIterations = o.newtonIterations;
  s.residualTolerance = o.residualTolerance;
  s.frameBudgetMs = o.frameBudgetMs;
  s.reuseStiffness = o.reuseStiffness;
  s.lbfgsPairs = o.lbfgsPairs;
  s.localNewton = o.localNewton;
  s.predictedStart = o.predictedStart;
  s.acceleratedStart = o.acceleratedStart;
  s.convergePieces = o.convergePieces;
  s.vertexGuard = o.energyGuard == EnergyGuard::Vertex;
  s.stiffnessTolerance = o.stiffnessTolerance;
  if (o.type == SolverType::Reference) return referenceSettings(s);
  s.multigrid = true;
  s.gridHandles = parseGridSetup(o.grid);
  MultigridSettings& mg = s.multigridSettings;
  mg.preSweeps = mg.postSweeps = o.fineSweeps;
  mg.jacobi = o.smoother == Smoother::Jacobi;
  mg.jacobiOnDevice = o.smoother == Smoother::Auto;
  mg.coarseCholesky = o.coarseSolver == CoarseSolver::Cholesky;
  mg.coarseIterations = o.coarseIterations;
  mg.cycles = o.cycles;
  mg.splitAggregates = o.splitAggregates;
  mg.pcg = o.pcgTolerance > 0.0;
  if (mg.pcg) mg.pcgTolerance = o.pcgTolerance;
  return s;
}

}  // namespace galsculpt
