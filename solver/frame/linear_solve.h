// The Newton system's solve, delta = H^-1 (-g): the Galerkin multigrid (its hierarchy on the
// host, multigrid.h, following the damage; its operators and cycles on the executor,
// multigrid_cycle.h) as V-cycles or as PCG's preconditioner, or for the reference CHOLMOD's
// Cholesky on the system in host memory (direct_solver.h). Anchored rows keep a zero step.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/frame/direct_solver.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/region_solve.h"
#include "solver/frame/step.h"
#include "solver/model/sim_model.h"
#include "solver/multigrid/multigrid.h"
#include "solver/multigrid/multigrid_cycle.h"

namespace galsculpt {

// Why a frame with these settings cannot run on the CUDA executor ("" when it can).
inline std::string cudaUnsupportedReason([[maybe_unused]] const SimModel& model,
                                         const StepSettings& s) {
  if (!s.multigrid()) return "the reference solver (direct sparse Cholesky) runs on the CPU only";
  return "";
}

template <typename Exec>
class LinearSolve {
 public:
  LinearSolve(Exec& ex, const SimModel& model, FrameData<Exec>& data)
      : ex_(ex), model_(model), d_(data), mg_(ex, model.pattern), region_(ex, data) {}

  // The hierarchy for the settings' handles, built again only when they change.
  void ensureHierarchy(const StepSettings& s, const std::vector<std::uint8_t>& damaged,
                       std::uint64_t damageRevision) {
    if (multigrid_ && gridHandles_ == s.gridHandles) return;
    multigrid_ = std::make_unique<Multigrid>(model_.pattern, model_.mesh.vertices, model_.edges,
                                             s.gridHandles);
    gridHandles_ = s.gridHandles;
    if (s.splitAggregates) multigrid_->updateDamage(model_.edges, damaged, damageRevision);
    mg_.upload(buildMultigridLayout(*multigrid_, model_.pattern));
    ++revision_;
  }

  // With splitAggregates, the hierarchy's aggregates split where the damage parts them (host).
  void followDamage(const StepSettings& s, const std::vector<std::uint8_t>& damaged,
                    std::uint64_t damageRevision) {
    if (s.multigrid() && s.splitAggregates &&
        multigrid_->updateDamage(model_.edges, damaged, damageRevision)) {
      mg_.upload(buildMultigridLayout(*multigrid_, model_.pattern));
      ++revision_;
    }
  }

  // What the multigrid carries between frames (MultigridCycle::keptCoarseMatrix).
  std::vector<double> keptCoarseMatrix() const { return mg_.keptCoarseMatrix(); }
  void adoptKeptCoarseMatrix(std::vector<double> m) { mg_.adoptKeptCoarseMatrix(std::move(m)); }

  // The multigrid's operators for the system just built (its fixed rows: the held vertices).
  // Not in a local iteration: its solve has no multigrid.
  void refresh(const StepSettings& s) {
    mg_.setFixed(d_.fixed.data());
    // Under PCG the V-cycle only preconditions: its smoother may read floats.
    mg_.refresh(d_.system.data(), s.coarseSolver == CoarseSolver::Cholesky, s.pcg());
  }

  // Whether PCG would return the null step: |b| = |g| (all 3n entries, as PCG reads them) within
  // its target (solve, MultigridCycle::pcg), which it checks before its first iteration (but
  // after a V-cycle). One host read, where PCG makes several; |g| goes to `bnorm`.
  bool nullStep(const StepSettings& s, double target, double& bnorm) {
    const double* g = d_.g.data();
    FrameScalars* sc = d_.sc();
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return g[i] * g[i]; }, &sc->r0);
    double r0 = 0.0;
    ex_.read(&sc->r0, &r0, 1);
    bnorm = std::sqrt(r0);
    lastStepNull_ = !(bnorm > std::max(s.pcgTolerance * std::max(bnorm, 1e-300), target));
    if (!lastStepNull_) return false;
    reduction_ = bnorm > 0.0 ? 1.0 : 0.0;  // what PCG returns after no iteration
    return true;
  }

  // Whether the null-step test is worth its read. On a device the read is a wait, made only
  // where the last step was null (a body at rest stays at rest a while); elsewhere PCG finds a
  // null step itself (no iteration, delta = 0: the same step) at the cost of the system's build
  // and the refresh, which a step that is not null needs anyway.
  bool nullTestPays() const { return Exec::kHostMemory || lastStepNull_; }

  // delta = H^-1 (-g) by the multigrid: V-cycles (the residual norms go to r0 and r1; no host
  // read) or PCG to `target` (absolute; its reduction and iterations go to the frame's scalars,
  // and to reduction() and iterations() once the frame read them: takeSolve). In a local
  // iteration, PCG on the region's rows (region_solve.h, its figures the same way; the multigrid
  // is not refreshed).
  void solve(const StepSettings& s, double target) {
    if (d_.local) {
      startFromZero();
      region_.launch(d_.system.data(), d_.rhs.data(), d_.delta.data(),
                     s.pcg() ? s.pcgTolerance : kRegionTolerance, target);
      figuresToScalars(region_.pcgScalars());
      return;
    }
    double* delta = d_.delta.data();
    double* b = d_.rhs.data();
    const std::uint8_t* fixed = d_.fixed.data();
    startFromZero();
    const double* a = d_.system.data();
    FrameScalars* sc = d_.sc();
    double* ap = d_.product.data();
    if (!s.pcg()) {  // (PCG sums |b|^2 itself; r0 and r1 are read only for the V-cycles)
      ex_.sum(
          3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return b[i] * b[i]; }, &sc->r0);
      mg_.cycles(a, b, delta, s);
      mg_.multiplyFine(a, delta, ap);
      ex_.sum(
          3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return (b[i] - ap[i]) * (b[i] - ap[i]); },
          &sc->r1);
    } else {
      mg_.pcgLaunch(a, b, delta, s, s.pcgTolerance, s.pcgMaxIterations, target);
      figuresToScalars(mg_.pcgScalars());
    }
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) {
      if (fixed[i / 3]) delta[i] = 0.0;
    });
    if (const double* failed = mg_.coarseFailure()) {  // a device's factorization's status
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc->coarseFailed = *failed; });
      coarseStatusInScalars_ = true;
    }
  }

  // Whether the read says that a device's dense factorization of the coarsest level, made
  // without a wait, failed: the solve then used no valid coarsest solve, and is to be made
  // again (the multigrid now solves the coarsest level by CG).
  bool coarseFactorFailed(const FrameScalars& read) {
    if (!coarseStatusInScalars_) return false;
    coarseStatusInScalars_ = false;
    return mg_.takeCoarseFailure(read.coarseFailed > 0.0);
  }

  // A PCG solve's reduction and iterations into the frame's scalars, where they ride the frame's
  // next read (takeSolve): the solve has no read of its own. Public only because nvcc refuses
  // extended lambdas in private member functions.
  void figuresToScalars(const typename MultigridPcg<Exec>::Scalars* pcg) {
    FrameScalars* sc = d_.sc();
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      const typename MultigridPcg<Exec>::Result r = MultigridPcg<Exec>::result(*pcg);
      sc->pcgReduction = r.reduction;
      sc->pcgIterations = r.iterations;
    });
    solveInScalars_ = true;
  }

  // The reference's linear solve: CHOLMOD on the system in host memory. A system that is not
  // positive definite leaves a NaN step, which fails the sub-step (retried with half the step).
  void solveDirect(const StepSettings& s) {
    double* delta = d_.delta.data();
    double* b = d_.rhs.data();
    FrameScalars* sc = d_.sc();
    startFromZero();
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc->r0 = sc->r1 = 0.0; });
    if constexpr (Exec::kHostMemory) {
      if (!direct_) direct_ = std::make_unique<DirectSolver>(model_.pattern);
      if (!direct_->solve(d_.system.data(), b, delta))
        delta[0] = std::numeric_limits<double>::quiet_NaN();
    } else {
      throw std::logic_error(cudaUnsupportedReason(model_, s));
    }
  }

  // b = -g (0 where the system holds a vertex still), delta = 0.
  void startFromZero() {
    double* delta = d_.delta.data();
    double* b = d_.rhs.data();
    const double* g = d_.g.data();
    const std::uint8_t* fixed = d_.solveFixed();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) {
      b[i] = fixed[i / 3] ? 0.0 : -g[i];
      delta[i] = 0.0;
    });
  }

  // A local iteration's relative PCG tolerance where the settings have no PCG (V-cycles).
  static constexpr double kRegionTolerance = 1e-2;

  // The figures of the last solve() from the frame's read after it (PCG's left them in the
  // frame's scalars); nothing where none were left there (V-cycles, a null step).
  void takeSolve(const FrameScalars& read) {
    if (!solveInScalars_) return;
    solveInScalars_ = false;
    reduction_ = read.pcgReduction;
    iterations_ += static_cast<int>(read.pcgIterations);
    lastStepNull_ = read.pcgIterations == 0.0;
  }

  // PCG's |r| / |b| of the last solve (or null step), once taken (takeSolve).
  double reduction() const { return reduction_; }
  // PCG iterations since resetIterations (a sub-step's).
  int iterations() const { return iterations_; }
  void resetIterations() { iterations_ = 0; }
  // Bumped whenever the hierarchy is uploaded again (what a captured solve bakes in).
  std::uint64_t revision() const { return revision_; }

 private:
  Exec& ex_;
  const SimModel& model_;
  FrameData<Exec>& d_;
  MultigridCycle<Exec> mg_;
  RegionSolve<Exec> region_;  // a local iteration's
  std::unique_ptr<Multigrid> multigrid_;
  std::unique_ptr<DirectSolver> direct_;  // the reference's (host memory only)
  std::vector<int> gridHandles_;
  std::uint64_t revision_ = 0;
  double reduction_ = 0.0;
  int iterations_ = 0;
  bool solveInScalars_ = false;         // the last solve's figures wait in the frame's scalars
  bool coarseStatusInScalars_ = false;  // and a device factorization's status
  bool lastStepNull_ = true;            // the last Newton step was null (a body starts at rest)
};

}  // namespace galsculpt
