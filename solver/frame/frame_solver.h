// The frame, written once: backward Euler's sub-steps as launches of an executor, run by the
// CPU executor (cpu_executor.h: oneTBB loops, the CPU backend and the reference) and by the CUDA
// one (gpu/cuda_executor.cuh). This class is the Newton solver and the table of contents; its
// parts each do one job over the arrays they share (frame_data.h):
//   frame_loop.h            sub-steps, retries, plastic flow and fracture re-solves (runFrame)
//   held_vertices.h         anchors on their paths and removed debris, per sub-step
//   substep_start.h         a sub-step's start: x_n, v_n, the target, the prediction kept or not
//   substep_end.h           a sub-step's end: the residual, finiteness, contact forces, velocities
//   accelerated_start.h     the free pieces' start on their paths with their acceleration
//   incremental_potential.h the potential, its gradient g and the Newton system H (the element
//                           pass in element_pass.h, the contact term in contact_term.h)
//   linear_solve.h          delta = H^-1 (-g): the Galerkin multigrid, or CHOLMOD for the reference
//   local_region.h          where an iteration after the first solves: the region of the residual
//   line_search.h           backtracking, lengthening and the vertex guard
//   piece_residual.h        the residual piece by piece; piece_tracker.h the pieces themselves
//   plastic_state.h         the plastic rest shapes and their return map
//   fracture_pass.h         which edges break
// Every sum is taken in a fixed order (gathers over fixed lists, fixed reduction trees), so a
// frame's bits do not depend on the thread count. The host reads the scalars (frame_scalars.h)
// once per Newton iteration and line-search trial; on the GPU everything between two reads is
// captured once as a CUDA graph and replayed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "solver/frame/accelerated_start.h"
#include "solver/frame/contact_term.h"
#include "solver/frame/fracture_pass.h"
#include "solver/frame/frame_damage.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/frame_loop.h"
#include "solver/frame/graph_key.h"
#include "solver/frame/held_vertices.h"
#include "solver/frame/host_shadow.h"
#include "solver/frame/incremental_potential.h"
#include "solver/frame/line_search.h"
#include "solver/frame/linear_solve.h"
#include "solver/frame/local_region.h"
#include "solver/frame/piece_residual.h"
#include "solver/frame/plastic_state.h"
#include "solver/frame/step.h"
#include "solver/frame/timing.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

template <typename Exec>
class FrameSolver {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  FrameSolver(Exec& ex, const SimModel& model)
      : ex_(ex),
        model_(model),
        d_(model),
        plastic_(ex, model),
        potential_(ex, model, d_, plastic_),
        contact_(potential_.contact()),
        lineSearch_(ex, d_, potential_),
        linear_(ex, model, d_),
        held_(ex, model, d_),
        region_(ex, d_),
        damage_(model, d_) {
    if (model.fracture.enabled) fracture_ = std::make_unique<FracturePass<Exec>>(ex, model);
    modelSize_ = std::max(boundingBox(model.mesh.vertices).size().norm(), 1e-12);
    double massNorm = 0.0;
    for (double m : model.mass) massNorm += 3.0 * m * m;
    massNorm_ = std::sqrt(massNorm);
  }

  // ---- the state shared with the host (SimState) ------------------------------------------

  // Brings the executor's memory up to date with `state` (uploads only what changed since the
  // last sync; on the CPU executor an upload is a copy).
  void syncIn(const SimState& state, const StepSettings& settings) {
    if (uploadIfChanged(state.x, hostX_, d_.x)) gradientAtX_ = false;
    uploadIfChanged(state.v, hostV_, d_.v);
    // Compared by content too: a backend may step several states (tests, undo snapshots).
    if (damage_.syncIn(state)) gradientAtX_ = false;
    if (model_.debrisRemoval > 0.0 && removedFor_ != damage_.changes()) {
      removedFor_ = damage_.changes();
      held_.updateRemovedDebris(damage_.census());
      gradientAtX_ = false;
    }
    held_.holdRemovedAt(state);
    if (plastic_.syncIn(state, d_.rest.data())) gradientAtX_ = false;
    time_ = state.time;
    colliderStates_ = state.colliders;
    for (size_t c = colliderStates_.size(); c < model_.colliders.size(); ++c)
      colliderStates_.push_back(initialColliderState(model_.colliders[c]));
    colliderStates_.resize(model_.colliders.size());
    d_.settings = &settings;
    anchors_ = &state.anchors;
    letGo_ = state.letGo;
    if (settings.multigrid()) linear_.ensureHierarchy(settings, damage_.host(), damage_.revision());
    // The stiffness frozen at x_n for damping, kept apart only with several Newton iterations
    // (allocated here: never inside a captured section).
    if (settings.newtonIterations > 1 && d_.frozen.size() != d_.stiffness.size())
      d_.frozen.resize(d_.stiffness.size());
  }

  // Writes positions, velocities, damage and plastic state back (positions and velocities
  // through the executor's pinned staging buffer, behind one wait).
  void syncOut(SimState& state) {
    downloadThroughShadows(ex_, d_.x, hostX_, state.x, d_.v, hostV_, state.v);
    damage_.syncOut(state);
    plastic_.syncOut(state);
    state.time = time_;
    state.colliders = colliderStates_;
    state.letGo = letGo_;  // taken by the first sub-step
  }

  // What the frame carries to the next beyond the state (StepBackend::carriedState).
  std::vector<double> carriedState() const { return linear_.keptCoarseMatrix(); }
  void adoptCarriedState(std::vector<double> carried) {
    linear_.adoptKeptCoarseMatrix(std::move(carried));
  }

  // One frame, from the host state to the host state.
  StepReport step(SimState& state, const StepSettings& settings) {
    syncIn(state, settings);
    Ops ops{*this};
    frameStart_ = Clock::now();
    StepReport report = runFrame(ops, settings);
    syncOut(state);
    return report;
  }

  // ---- the frame loop's operations (frame_loop.h) ---------------------------------------

  struct Saved {
    double time;
    std::vector<ColliderState> colliders;
    bool letGo;  // a retried sub-step starts as the first try did
  };
  struct Ops {
    FrameSolver& s;
    Saved save() { return s.save(); }
    void restore(const Saved& saved, bool keepDamage) { s.restore(saved, keepDamage); }
    SubstepOutcome substep(double h) { return s.substep(h); }
    bool plastic() const { return s.plastic_.active(); }
    int plasticUpdate() { return s.plasticUpdate(); }
    bool fractures() const { return s.model_.fracture.enabled; }
    FractureReport fracturePass() { return s.fracturePass(); }
    double time() const { return s.time_; }
    void setTime(double t) { s.time_ = t; }
  };

  Saved save() {
    ex_.copy(d_.savedX.data(), d_.x.data(), 3 * d_.n);
    ex_.copy(d_.savedV.data(), d_.v.data(), 3 * d_.n);
    plastic_.save();
    return Saved{time_, colliderStates_, letGo_};
  }
  // Damage never needs restoring: a failed sub-step is rolled back before its fracture pass,
  // and a fracture re-solve keeps the new damage.
  void restore(const Saved& saved, bool /*keepDamage*/) {
    gradientAtX_ = false;
    ex_.copy(d_.x.data(), d_.savedX.data(), 3 * d_.n);
    ex_.copy(d_.v.data(), d_.savedV.data(), 3 * d_.n);
    plastic_.restore(d_.rest.data());
    time_ = saved.time;
    colliderStates_ = saved.colliders;
    letGo_ = saved.letGo;
  }

  // ---- one backward-Euler sub-step: the Newton solver ----------------------------------------

  // Newton iterations until the residual is within the tolerance (converged), Newton's step
  // test is met, the iterations are spent or the frame's time budget is (not converged).
  SubstepOutcome substep(double h) {
    const StepSettings& s = *d_.settings;
    SubstepOutcome result;
    beginSubstep(h);
    bool stationary = false;
    bool reuse = false;  // solve with the last iteration's stiffness (a chord step)
    bool chordFailed = false;
    bool local = false;  // this iteration solves only in the region (local_region.h)
    double lastResidual = 0.0;
    for (int it = 0; it < s.newtonIterations; ++it) {
      // Ctrl-C or SIGTERM: a frame with many sub-steps or slow iterations stops within one.
      if (stopRequested()) {
        result.ok = false;
        result.stopped = true;
        return result;
      }
      d_.local = local;
      const NewtonOutcome n = newtonIteration(h, it, reuse, result);
      d_.local = false;
      if (local) ++result.localIterations;
      if (n == NewtonOutcome::Restart) {
        --it;
        continue;
      }
      if (n == NewtonOutcome::Failed) {
        result.ok = false;
        return result;
      }
      // Newton's step test ends the iterations only where no residual tolerance is set. A short
      // step is no proof of a solution where the Newton matrix is not the Hessian (projected,
      // or a chord's): only the residual decides that a frame has converged.
      if (n == NewtonOutcome::Converged && s.residualTolerance <= 0.0) {
        stationary = true;
        break;
      }
      if (n == NewtonOutcome::Stalled) break;
      if (it + 1 == s.newtonIterations) break;  // endSubstep measures the last one
      if (s.frameBudgetMs > 0.0 && msSince(frameStart_) > s.frameBudgetMs) break;
      if (!potential_.residualAtTrials()) continue;  // nothing reads it
      const double residual = residualAt();
      if (residual <= s.residualTolerance && piecesWithinTolerance(residual, accepted_.forces))
        break;
      // Keep the stiffness while it still cuts the residual at least in half. Once a chord step
      // has not, the stiffness moves with the iterate (cracks opening and closing, contacts
      // coming and going): every later iteration of the sub-step takes a fresh one.
      chordFailed = chordFailed || (reuse && !(residual < 0.5 * lastResidual));
      // Nor is a chord taken after a step that opened or closed cracks in more than
      // kChordSwitchedElements elements: each such element's stiffness is another matrix (a
      // closed crack's edge carries the faces' contact, an open one nothing), and the chord steps
      // with the wrong one.
      reuse = s.reuseStiffness && !chordFailed && switchedCracks_ <= kChordSwitchedElements &&
              !systemSkipped_;
      // Where the body is within the tolerance but for a region, the next iteration solves only
      // there (local_region.h), unless the last local iteration failed to halve the residual
      // (then the whole body again). Not where only a piece is above its own tolerance: its
      // residual is a small share of the body's. A local system holds the other rows still: no
      // chord is taken on it, nor after it.
      const bool wasLocal = local;
      local = s.localNewton && s.multigrid() && residual > s.residualTolerance &&
              !(wasLocal && !(residual < 0.5 * lastResidual)) &&
              (accepted_.fromTrial && potential_.formsRegionAtTrials()
                   ? region_.decide(accepted_.trialRead)
                   : region_.choose(s.residualTolerance * std::max(weight(), forceScale_)));
      if (local || wasLocal) reuse = false;
      lastResidual = residual;
    }
    endSubstep(h, result);
    // With a residual tolerance, the residual alone says whether the sub-step converged (see
    // the loop above), the body's and, with convergePieces, each piece's; without one (the
    // reference), the step test is the criterion.
    result.converged = s.residualTolerance > 0.0
                           ? result.residual <= s.residualTolerance &&
                                 (!s.convergePieces || result.pieceResidual <= s.residualTolerance)
                           : stationary;
    result.cgIterations = linear_.iterations();
    if (result.ok) {
      for (size_t c = 0; c < model_.colliders.size(); ++c)
        if (model_.colliders[c].motion.rigidPendulum())
          advancePendulum(model_.colliders[c], colliderStates_[c], h, contactMoments_[c],
                          model_.gravity);
      time_ += h;
    }
    return result;
  }

  // With convergePieces, whether every measured piece (piece_residual.h) is within the
  // tolerance of its own loads at the accepted positions (g and accepted_.forces, from
  // residualAt(); `residual` the body's there). The body's residual is one 2-norm and a small
  // piece's share of it is small, so a solve to the body's target would leave such a piece where it
  // is. A piece above its tolerance by a factor R therefore caps PCG's absolute target (and the
  // null step's) for the rest of the sub-step at 0.5 / R of the body's residual or of the body's
  // own target, whichever is smaller: an inexact Newton forcing term set by the worst piece, below
  // the residual so that a solve always has something to do. `forces`: the elastic and contact
  // forces beside g (accepted_.forces there; grad in newtonStep).
  bool piecesWithinTolerance(double residual, const double* forces) {
    const StepSettings& s = *d_.settings;
    if (!s.convergePieces) return true;
    const double worst =  // the accepted trial's where it formed it
        accepted_.fromTrial && forces == accepted_.forces && potential_.formsPiecesAtTrials()
            ? accepted_.trialRead.trialWorstPiece
            : pieceResidual_.measure(ex_, damage_.pieces(), d_.g.data(), forces, d_.fixed.data(),
                                     d_.mass.data(), model_.gravity.norm());
    if (worst <= s.residualTolerance) return true;  // (-1: fewer than two measured pieces)
    const double share = 0.5 * s.residualTolerance / worst;
    pieceTargetCap_ =
        std::min(pieceTargetCap_, share * std::min(residual, 0.5 * s.residualTolerance) *
                                      std::max(weight(), forceScale_));
    return false;
  }

  // The backward-Euler residual at the accepted positions over the force scale, with g there
  // and the pass terms' forces (accepted_.forces). The accepted trial formed them where the
  // frame tests residuals (IncrementalPotential::residualAtTrials) and the line search's last
  // read holds its sums: no read. Otherwise they are formed and read here.
  double residualAt() {
    if (accepted_.fromTrial) {
      ex_.copy(d_.g.data(), d_.trialG.data(), 3 * d_.n);
      accepted_.forces = d_.trialForces.data();
      return relativeResidual(accepted_.trialRead);
    }
    potential_.acceptedResidual();
    accepted_.forces = d_.tmp.data();
    FrameScalars read;
    ex_.read(d_.sc(), &read, 1);
    return relativeResidual(read);
  }

  // The residual over the force scale: the larger of the body's weight and the elastic and
  // contact forces acting on it, so that a frame is solved to the same fraction of its loads
  // whether it hangs under gravity or takes a striker's meganewtons.
  double relativeResidual(const FrameScalars& read) {
    forceScale_ = std::max(weight(), std::sqrt(read.forceScale));
    return std::sqrt(read.residual) / forceScale_;
  }

  // |f_ext| = |g| |m| over the vertices (massNorm_ is over the 3n DOFs: |m| sqrt 3), at least 1 g.
  double weight() const {
    const double perDofMass = massNorm_ / std::sqrt(3.0);
    return std::max(model_.gravity.norm() * perDofMass, 9.81 * perDofMass);
  }

  // x_n, v_n and the inertial target from the state; anchored vertices on their paths.
  void beginSubstep(double h);

  // Pieces nothing holds start on their path with their acceleration (accelerated_start.h).
  // Called once the held vertices and the colliders are placed (fixed and the poses are the
  // sub-step's).
  void startPiecesAccelerated(double h, bool gradientAtXn);

  // Newton starts from x_n when the prediction x_n + h v_n turned an intact element inside out
  // (the line search only refuses steps that invert more: it would keep those). `read`: the
  // scalars after the first Newton step.
  bool dropInvertingPrediction(const FrameScalars& read);

  // Converged: the step was below Newton's step test; Stalled: no step length descends (a
  // failure before any progress, else the end of the iterations, converged only if the
  // residual says so).
  // Restart: the predicted start was dropped, the iteration runs again from x_n.
  enum class NewtonOutcome { Continue, Converged, Stalled, Failed, Restart };

  // One Newton iteration: the step (assembled, solved, measured, its full length tried),
  // shortened while it raises the incremental potential, then accepted.
  NewtonOutcome newtonIteration(double h, int it, bool reuse, SubstepOutcome& result) {
    const StepSettings& s = *d_.settings;
    const auto t0 = Clock::now();
    const double elementsBefore = result.msElements;
    gradientAtX_ = false;  // the element passes below overwrite elemGrad
    accepted_.fromTrial = false;
    // Structural changes first (host): the hierarchy follows the damage.
    linear_.followDamage(s, damage_.host(), damage_.revision());
    // The Newton step and its full-length trial: launches only (part of the device program
    // open; a graph replayed where programs are off), unless a dense Cholesky, PCG or the direct
    // solve needs host reads in between.
    const bool capturable =
        s.multigrid() && s.coarseSolver != CoarseSolver::Cholesky && !s.pcg() && !d_.local;
    if (capturable) {
      ex_.captured(0, graphKey(h, it) ^ (reuse ? 0x9e3779b97f4a7c15ull : 0),
                   [&] { newtonStep(it, reuse, result); });
    } else {
      newtonStep(it, reuse, result);
    }
    FrameScalars read;
    ex_.read(d_.sc(), &read, 1);
    linear_.takeSolve(read);
    if (linear_.coarseFactorFailed(read)) {
      // A device's dense coarsest factorization failed after all (its status rode this read):
      // the step is solved again, the coarsest level by CG.
      linear_.solve(s, pcgTarget());
      potential_.stepMeasures();
      potential_.evaluateTrial(1.0);
      ex_.read(d_.sc(), &read, 1);
      linear_.takeSolve(read);
    }
    if (it == 0 && dropInvertingPrediction(read)) {
      result.msSolve += msSince(t0);
      if constexpr (Exec::kHostMemory) result.msSolve -= result.msElements - elementsBefore;
      return NewtonOutcome::Restart;
    }
    ++result.newtonIterations;
    if (!reuse && s.stiffnessTolerance > 0.0) result.keptStiffnesses += read.kept;
    const double stepLength = lineSearch_.search(result, read, linear_.reduction());
    switchedCracks_ = s.reuseStiffness ? read.switched : 0.0;
    result.msSolve += msSince(t0);
    if constexpr (Exec::kHostMemory) result.msSolve -= result.msElements - elementsBefore;
    if (stepLength < 0.0) return NewtonOutcome::Failed;
    if (stepLength <
        LineSearch<Exec>::kShortestStep)  // no descent: a failure only before any progress
      return result.newtonIterations == 1 ? NewtonOutcome::Failed : NewtonOutcome::Stalled;
    // Accept: the trial just evaluated is the new iterate (its energy and gradient too).
    ex_.copy(d_.x.data(), d_.trial.data(), 3 * d_.n);
    ex_.copy(d_.acceptedGrad.data(), d_.trialGrad.data(), 3 * d_.n);
    ex_.copy(d_.elemEnergy.data(), d_.trialEnergy.data(), d_.tets);
    ex_.copy(d_.elemInverted.data(), d_.trialInverted.data(), d_.tets);
    gradientAtX_ = true;                  // the line search's last trial is the accepted one
    if (potential_.residualAtTrials()) {  // and its residual the accepted positions'
      accepted_.fromTrial = true;
      accepted_.trialRead.residual = read.trialResidual;
      accepted_.trialRead.forceScale = read.trialForceScale;
      accepted_.trialRead.trialInverted = read.trialInverted;
      accepted_.trialRead.bad = read.trialBad;
      accepted_.trialRead.regionVertices = read.regionVertices;
      accepted_.trialRead.freeVertices = read.freeVertices;
      accepted_.trialRead.trialWorstPiece = read.trialWorstPiece;
    }
    result.elasticEnergy = read.trialElastic;
    // Newton's step test on the full step: a step shortened to nothing says nothing about
    // stationarity.
    return read.deltaMax < s.tolerance * modelSize_ ? NewtonOutcome::Converged
                                                    : NewtonOutcome::Continue;
  }

  // Assembles and solves the Newton system at x, measures the step and tries its full length.
  // With `reuse`, the system (stiffness, contact, the multigrid's operators) stays the last
  // iteration's and only the gradient is new: the accepted trial's, already evaluated.
  void newtonStep(int it, bool reuse, SubstepOutcome& result) {
    const StepSettings& s = *d_.settings;
    const double* x = d_.x.data();
    const auto tElements = Clock::now();
    // The pass terms at x: the element pass (with `reuse` the accepted trial's) and contact.
    potential_.passTerms().atIterate(x, reuse, d_.grad.data());
    if (!reuse) {
      // Phases are timed where launches run as they are issued (the CPU); on the GPU they run
      // as one graph and all of it counts as solve.
      if constexpr (Exec::kHostMemory) result.msElements += msSince(tElements);
      const bool frozenCopy = it == 0 && s.newtonIterations > 1;
      if (frozenCopy) ex_.copy(d_.frozen.data(), d_.stiffness.data(), d_.stiffness.size());
      d_.frozenIsK = !(frozenCopy || (it > 0 && s.newtonIterations > 1));
    }
    // Under PCG a fresh iteration may find the gradient already within the solve's target: the
    // step is null, and nothing past the gradient is needed (takeNullStep).
    const bool mayBeNull = !reuse && !d_.local && s.multigrid() && s.pcg() && s.skipNullSolves &&
                           linear_.nullTestPays();
    potential_.dampedProduct(x, d_.dampedK.data());
    potential_.backwardEulerGradient(x, d_.grad.data(), d_.dampedK.data(), d_.g.data());
    double bodyResidual = 0.0;
    // A null step for the body is none for a piece still above its own tolerance: it sets the
    // cap, and this iteration solves (a settled body can hide a piece that still spins).
    if (mayBeNull && nullStep(bodyResidual) &&
        piecesWithinTolerance(bodyResidual, d_.grad.data())) {
      takeNullStep();
      return;
    }
    systemSkipped_ = false;
    if (!reuse) potential_.buildSystem(x);
    if (s.multigrid()) {
      if (!reuse && !d_.local) linear_.refresh(s);  // (a local solve has no multigrid)
      // A chord step's direction is L-BFGS's where pairs are kept (a chord is never local).
      linear_.solve(s, pcgTarget());
    } else {
      linear_.solveDirect(s);
    }
    potential_.stepMeasures();
    potential_.evaluateTrial(1.0);
  }

  // Whether PCG would return the null step (LinearSolve::nullStep); then `bodyResidual` is the
  // body's relative residual there (|g| over the last force scale).
  bool nullStep(double& bodyResidual) {
    double bnorm = 0.0;
    if (!linear_.nullStep(*d_.settings, pcgTarget(), bnorm)) return false;
    bodyResidual = bnorm / std::max(weight(), forceScale_);
    return true;
  }

  // PCG's absolute target: never further than half the residual the sub-step must reach (an
  // inexact Newton step), less while a piece is above its own (piecesWithinTolerance).
  double pcgTarget() const {
    return std::min(0.5 * d_.settings->residualTolerance * std::max(weight(), forceScale_),
                    pieceTargetCap_);
  }

  // The null step, taken without what it would not use: the system, the multigrid's operators
  // and PCG's first V-cycle. Its trial (at x) is still evaluated: the trial's element pass is
  // the one whose energies and gradients the frame reports and the next sub-step's start reads,
  // and the stiffness pass's (SIMD lanes) may differ from them in the last bits, which a frame
  // that follows from the state alone cannot allow. At rest most frames are one null step.
  // The system was not built: the next iteration of the sub-step takes a fresh one.
  void takeNullStep() {
    double* delta = d_.delta.data();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { delta[i] = 0.0; });
    potential_.stepMeasures();
    potential_.evaluateTrial(1.0);
    systemSkipped_ = true;
  }

  // A chord step is taken while at most this many elements changed their open cracks since the
  // stiffness was evaluated (substep). A count, not a share of the body: what a switched element
  // gets wrong in the chord's step is local to it.
  static constexpr double kChordSwitchedElements = 64;

  // The sub-step's end (substep_end.h): the residual at the accepted positions (relative to
  // the body's 1 g weight), contact forces, finiteness, velocities; one captured section and
  // one read, or none where the accepted trial's read holds it all.
  void endSubstep(double h, SubstepOutcome& result);
  void finishSubstep(double h);  // (endSubstep's captured section)

  // Everything a captured Newton step bakes in: a replay is valid only for the same key.
  std::uint64_t graphKey(double h, int iteration) const {
    return GraphKey()
        .mixDouble(h)
        .mix(static_cast<std::uint64_t>(iteration))
        .mixSettings(*d_.settings)
        .mix(linear_.revision())
        .mix(d_.anchorCount)
        .mix(static_cast<std::uint64_t>(contact_.colliders()))
        .mixPointer(d_.anchorVertices.data())
        .mixPointer(d_.anchorTargets.data())
        .mixPointer(contact_.poses())
        .mixPointer(plastic_.inverse())
        .mix(plastic_.active())
        .mix(d_.local)
        .value();
  }

  // ---- plasticity and fracture --------------------------------------------------------------

  int plasticUpdate() {
    gradientAtX_ = false;  // rest shapes flow
    return plastic_.returnMap(d_.x.data(), d_.damaged.data(), d_.tetVertices.data(),
                              d_.tetEdges.data(), d_.rest.data(), d_.elemEnergy.data());
  }

  // Each edge's stress as the fracture pass sees it at `state` (element maximum, then the
  // kernel mean when the field has one), 0 on damaged edges: for tests and views. The kernel
  // mean is taken on every edge, not only near hot ones; no damage changes.
  // Needs the model's fracture field.
  std::vector<double> edgeStress(const SimState& state, const StepSettings& settings) {
    syncIn(state, settings);
    fracture_->evaluate(potential_.elastic().inputs(), d_.x.data(), d_.damaged.data(), true);
    std::vector<double> ratio(d_.edges), out(d_.edges, 0.0);
    if (d_.edges > 0) ex_.download(fracture_->stressRatio(), ratio.data(), ratio.size());
    for (int e = 0; e < d_.edges; ++e)
      if (!damage_.host()[e]) out[e] = ratio[e] * model_.fracture.threshold[e];
    return out;
  }

  FractureReport fracturePass() {
    FractureReport report =
        fracture_->findBreaks(potential_.elastic().inputs(), d_.x.data(), d_.damaged.data());
    if (report.newlyDamaged > 0) {
      fracture_->markBroken(d_.damaged.data());
      report.newlyDamaged += damage_.takeBreaks();
      gradientAtX_ = false;
    }
    return report;
  }

 private:
  Exec& ex_;
  const SimModel& model_;
  FrameData<Exec> d_;
  PlasticState<Exec> plastic_;
  IncrementalPotential<Exec> potential_;
  ContactTerm<Exec>& contact_;  // the potential's: the colliders' poses and forces
  LineSearch<Exec> lineSearch_;
  LinearSolve<Exec> linear_;
  HeldVertexSet<Exec> held_;
  LocalRegion<Exec> region_;
  FrameDamage<Exec> damage_;
  AcceleratedStart<Exec> accelerated_;            // the pieces' starts (startPiecesAccelerated)
  PieceResidual<Exec> pieceResidual_;             // the residual piece by piece
  std::unique_ptr<FracturePass<Exec>> fracture_;  // with the model's fracture field
  const std::vector<AnchorConstraint>* anchors_ = nullptr;  // the stepped state's
  double time_ = 0.0, modelSize_ = 1.0, massNorm_ = 0.0;
  double forceScale_ = 0.0;      // the last residual's scale (N): the next solves' target
  double switchedCracks_ = 0.0;  // elements whose open cracks the last accepted step changed
  // PCG's absolute target at most this in this sub-step (piecesWithinTolerance).
  double pieceTargetCap_ = std::numeric_limits<double>::infinity();
  Clock::time_point frameStart_ = Clock::now();
  bool predicted_ = false;      // this sub-step's Newton started from x_n + h v_n, not yet checked
  bool letGo_ = false;          // SimState::letGo, until a sub-step starts
  bool systemSkipped_ = false;  // the last iteration's null step built no system (takeNullStep)
  // The residual at the accepted positions (residualAt): whether the accepted trial formed it
  // (IncrementalPotential::residualAtTrials) and its sums, until the next iteration starts; and
  // the forces beside g there (trialForces or tmp).
  struct {
    bool fromTrial = false;
    FrameScalars trialRead;
    const double* forces = nullptr;
  } accepted_;
  // Whether elemGrad holds every element's gradient at x under the current damage, rest shapes
  // and removed debris: true from a Newton iteration's accept until x or any of those changes
  // (what the pieces' start reads at x_n instead of evaluating them again).
  bool gradientAtX_ = false;
  std::vector<ColliderState> colliderStates_;  // the stepped state's, advanced per sub-step
  std::vector<double> contactMoments_;         // (nColliders) the last sub-step's, N m
  // Host shadows: what the executor holds, to upload only changes.
  std::vector<double> hostX_, hostV_;
  std::uint64_t removedFor_ = 0;  // the damage change the removed debris is for (0: none yet)
};

}  // namespace galsculpt

#include "solver/frame/substep_end.h"    // (the sub-step's end: the residual, the velocities)
#include "solver/frame/substep_start.h"  // (the sub-step's start: x_n, v_n, the prediction)
