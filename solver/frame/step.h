// One frame of implicit backward Euler.
//
// Positions solve the incremental potential
//   E(x) = 1/(2h^2) |x - x_n - h v_n|_M^2 + Psi(x) - f_ext . x + 1/(2h) |x - x_n|_D^2,
// with D = alpha M + beta K(x_0) (Rayleigh damping; x_0 is where Newton starts: x_n, or the
// inertial prediction x_n + h v_n with predictedStart). One Newton step from x_n is exactly the
// paper's linearized system (eq. 3 / eq. 8): (M + h D + h^2 K) dv = h (f_ext - f_int - (D + hK)
// v_n). StepSettings{} takes that one step; the scenes' converged preset iterates Newton until the
// residual is within residualTolerance of the force scale; the reference solver iterates Newton
// with a backtracking line search and a direct sparse solve (CHOLMOD) to a tight tolerance.
// Anchored vertices are Dirichlet conditions: they sit on their prescribed path and their rows
// are removed.
// A Newton step that would raise the incremental potential is shortened (backtracking), which
// keeps huge loads from exploding; a frame that still produces NaN or cannot descend is rolled
// back and retried with halved sub-steps, each retry counted as a warning.
#pragma once

#include <vector>

#include "solver/fracture/fracture.h"
#include "solver/frame/frame_statistics.h"
#include "solver/model/sim_model.h"
#include "solver/model/solver_options.h"

namespace galsculpt {

// Numerical settings only: what the body is and what acts on it is the model's (SimModel:
// gravity, damping, colliders, fracture field) or the state's (anchors). The solver options
// (solver/model/solver_options.h: one row each, documented in docs/scenes.md) are its base, read
// by the frame and the multigrid as they are; beside them, what follows from the scene (time
// step, sub-steps) and the frame's own constants.
//
// StepSettings{} is the paper's one linearized step solved directly (the options' `paper`
// column with a direct solve, `type` reference, and no line search): tests start from it.
struct StepSettings : SolverOptions {
  StepSettings();

  double dt = 1.0 / 60.0;
  int substeps = 1;
  bool lineSearch = false;
  // Newton's step test: with residualTolerance 0 (the reference), Newton stops and has
  // converged when |dx|_inf < tolerance * model size; otherwise the residual alone decides
  // (residualTolerance: a sub-step has converged when its backward-Euler residual on the free
  // DOFs is at most this times the force scale, the larger of the body's weight |M g| (at least
  // 1 g) and the elastic and contact forces on its free vertices; a frame that ends above it is
  // reported, StepReport::converged, whatever the settings).
  double tolerance = 1e-9;
  // Under PCG, a fresh Newton iteration whose gradient is already within the solve's target
  // takes its null step without building the system, refreshing the multigrid or running PCG's
  // first V-cycle: the same step, less work. Off only to compare (tests).
  bool skipNullSolves = true;
  // The multigrid's handle counts, finest coarse level first (parseGridSetup of `grid`).
  std::vector<int> gridHandles = {50};
  int maxRetries = 4;          // halvings of the step after NaN or explosion
  int pcgMaxIterations = 100;  // PCG's iterations per solve, at most
  // With the model's fracture field enabled, the fracture pass runs after every sub-step. Solves
  // of a sub-step while its fracture pass keeps breaking edges (1: the paper's one pass per
  // step; more let a crack run within a step, at the cost of re-solving).
  int fractureIterations = 1;

  // Each Newton step's linear solve: the Galerkin multigrid, or CHOLMOD's Cholesky.
  bool multigrid() const { return type == SolverType::Multigrid; }
  // CG preconditioned by one V-cycle per iteration, to pcgTolerance (else V-cycles alone).
  bool pcg() const { return pcgTolerance > 0.0; }
  // A Newton step that raised the potential is shortened first at the vertices whose share
  // rose (line_search.h), else backed off as a whole.
  bool vertexGuard() const { return energyGuard == EnergyGuard::Vertex; }
};

// The frame's settings for `options` at time step `dt` in `substeps` sub-steps; a `reference`
// type gives the reference solver's (referenceSettings: Newton with line search and a direct
// solve), which keeps only the start options (predicted, accelerated, pieces).
StepSettings stepSettings(const SolverOptions& options, double dt, int substeps);

// The reference solver's settings: Newton with line search to a tight tolerance.
StepSettings referenceSettings(StepSettings base);

// One frame's figures (frame_statistics.h) and the colliders' forces.
struct StepReport : FrameStatistics {
  std::vector<Vec3> contactForces;  // (nColliders) force of each collider on the body, N
  // A stop was asked for within the frame (solver/io/stop_request.h): it was left unfinished.
  bool stopped = false;
};

// Elastic energy of positions `x`; the gradient (3 nVerts) and, when `hessian` is given, the
// stiffness (projected to SPD), assembled on the host over element colours (deterministic).
// Not the frame's assembly (frame_solver.h): an independent one, for tests (derivatives against
// finite differences, multigrid operators) and tools.
// Uses the state's damage and plastic rest shapes, not its positions.
double assembleElastic(const SimModel& model, const std::vector<Vec3>& x, const SimState& state,
                       Eigen::VectorXd& gradient, BlockSparseMatrix* hessian);

// The elastic energy's gradient summed over `vertices` (the elements' pull on them, negated: an
// anchor's reaction), evaluating only the elements that touch them; equal to assembleElastic's
// gradient summed over the same vertices.
Vec3 elasticGradientSum(const SimModel& model, const std::vector<Vec3>& x, const SimState& state,
                        const std::vector<int>& vertices);

}  // namespace galsculpt
