#include "solver/model/solver_options.h"

#include <algorithm>
#include <stdexcept>

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
    {BackendRequest::Auto, "auto"},
    {BackendRequest::Cpu, "cpu"},
    {BackendRequest::Cuda, "cuda"},
    {BackendRequest::DeviceLike, "device-like"}};

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

std::vector<int> parseGridSetup(const std::string& grid) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t slash = grid.find('/', start);
    parts.push_back(grid.substr(start, slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  if (parts.size() < 2 || parts.back() != "all") {
    throw std::invalid_argument(
        "grid '" + grid +
        "' must list coarse vertex counts and end in 'all', e.g. 50/all or 50/1000/all");
  }
  std::vector<int> counts;  // coarse to fine as written
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (p.empty() || p.size() > 9 || p.find_first_not_of("0123456789") != std::string::npos) {
      throw std::invalid_argument("grid level '" + p + "' is not a vertex count");
    }
    const int n = std::stoi(p);
    if (n < 1 || (!counts.empty() && n <= counts.back())) {
      throw std::invalid_argument(
          "grid levels must be positive and increase from coarse to fine, got '" + grid + "'");
    }
    counts.push_back(n);
  }
  std::reverse(counts.begin(), counts.end());  // finest coarse level first
  return counts;
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

}  // namespace galsculpt
