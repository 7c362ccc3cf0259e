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
#include "solver/multigrid/multigrid.h"

namespace galsculpt {

// Numerical settings only: what the body is and what acts on it is the model's (SimModel:
// gravity, damping, colliders, fracture field) or the state's (anchors).
struct StepSettings {
  double dt = 1.0 / 60.0;
  int substeps = 1;
  int newtonIterations = 1;  // the most Newton iterations a sub-step takes (1: the paper's step)
  bool lineSearch = false;
  // Newton's step test: with residualTolerance 0 (the reference), Newton stops and has
  // converged when |dx|_inf < tolerance * model size; otherwise the residual alone decides.
  double tolerance = 1e-9;
  // A sub-step has converged when its backward-Euler residual (free DOFs) is at most this times
  // the force scale: the larger of the body's weight |M g| (at least 1 g) and the elastic and
  // contact forces on its free vertices. Newton stops there. A frame that ends above it is
  // reported (StepReport::converged), whatever the settings.
  double residualTolerance = 1e-2;
  // After a sub-step's first Newton iteration, solve with the stiffness (and multigrid
  // operators) already built while that still halves the residual each iteration: a chord step
  // costs a gradient and a solve, not an assembly, a projection and a Galerkin refresh.
  bool reuseStiffness = false;
  // > 0: a chord step's direction is L-BFGS's (secant_history.h): the chord's matrix, solved by
  // the multigrid, corrected by the sub-step's last lbfgsPairs steps and gradient changes.
  int lbfgsPairs = 0;
  // Under PCG, a fresh Newton iteration whose gradient is already within the solve's target
  // takes its null step without building the system, refreshing the multigrid or running PCG's
  // first V-cycle: the same step, less work. Off only to compare (tests).
  bool skipNullSolves = true;
  // > 0: within a sub-step, an intact element keeps the stiffness of an earlier Newton iteration
  // while no entry of its deformation gradient has moved more than this since (its energy and
  // force are always evaluated), and the 3x3 blocks made of kept stiffnesses only are not
  // gathered again. The Newton system is then approximate where strains moved less than this;
  // the gradient and the residual stay exact. Nothing is kept across sub-steps: a frame's result
  // follows from the state alone. 0: every element every time.
  double stiffnessTolerance = 0.0;
  // With residualTolerance: after an iteration that leaves the residual above it, the next
  // iteration solves only in the region where the residual is (local_region.h: the fewest
  // vertices outside which |g| is within kOutsideShare of the target, grown by kRings rings of
  // neighbours), holding the rest of the body still, when that region is at most kMostShare of
  // the free vertices; its elements alone are evaluated. The residual checked after it is the
  // whole body's. A frame where a brush moves a small part of a body costs in proportion to it.
  // With the multigrid only (the reference's direct solve takes the whole system).
  bool localNewton = false;
  // Newton starts from the inertial prediction x_n + h v_n instead of x_n: for a body in motion
  // it is much nearer the solution (a free fall is off by h^2 g only), which saves Newton and CG
  // iterations. A prediction that turns any intact element inside out is dropped for x_n. The
  // damping stiffness is taken where Newton starts (the reference keeps this setting, so it
  // solves the same equations). Off, the first Newton step is the paper's linearized system.
  bool predictedStart = false;
  // With predictedStart: each piece that no anchor, removed debris or collider holds starts
  // from x_n + h (v_n + h a) / (1 + h alpha), a = g + F / m its centre of mass's acceleration at
  // x_n (F: the push of the pieces it touches), instead of the straight line
  // (accelerated_start.h): pieces falling together off a cut body start where they go. Only
  // the start changes (with stiffness damping, K(x_0) too, but only in the elements between
  // pieces: the start moves each piece rigidly).
  bool acceleratedStart = true;
  // When the full Newton step raises the potential, first shorten it only at the vertices whose
  // share of the potential rose (a few rounds, re-evaluating only the elements around them), and
  // back the whole step off only if that fails: a step that overshoots next to a few vertices (a
  // brush that has just moved or let go of them) still moves the rest of the body, at the cost
  // of the elements around those vertices instead of a full energy pass per halving.
  bool vertexGuard = false;
  // With residualTolerance: a sub-step has converged only when every piece of more than
  // kMeasuredPieceVertices vertices is also within the tolerance of its own loads
  // (piece_residual.h), and Newton iterates on until it is; off, the body's residual alone
  // decides and the pieces' is only reported.
  bool convergePieces = false;
  // Milliseconds a frame may spend before its sub-steps stop iterating Newton (0: no limit; the
  // app's interactive budget). A frame stopped by it is reported as not converged.
  double frameBudgetMs = 0.0;
  // Linear solver of each Newton step: CHOLMOD's Cholesky, or the Galerkin multigrid.
  bool multigrid = false;
  std::vector<int> gridHandles = {50};  // handle counts, finest coarse level first
  MultigridSettings multigridSettings;
  int maxRetries = 4;  // halvings of the step after NaN or explosion
  // With the model's fracture field enabled, the fracture pass runs after every sub-step. Solves
  // of a sub-step while its fracture pass keeps breaking edges (1: the paper's one pass per
  // step; more let a crack run within a step, at the cost of re-solving).
  int fractureIterations = 1;
};

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
