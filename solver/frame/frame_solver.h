// The frame, written once: backward Euler's sub-step as launches of an executor, run by the CPU
// executor (cpu_executor.h: oneTBB loops, the CPU backend and the reference) and by the CUDA one
// (gpu/cuda_executor.cuh). Nothing above the element math exists anywhere else.
//
// Per sub-step: the element pass (one item per tet: the shared element kernels, damage from
// the edge flags, plastic rest shapes) writes energies, forces and the upper 3x3 blocks of the
// 12x12 stiffness per element; gathers (one item per vertex, per 3x3 block, each over its own
// list of contributions in a fixed order) assemble them into the fixed pattern without atomics,
// so the sums are the same for any thread count and on either executor; then the system matrix,
// the right-hand side, the linear solve (the Galerkin multigrid, multigrid_cycle.h, or for the
// reference CHOLMOD's Cholesky, direct_solver.h) and the energy-guarded step. The host reads a
// handful of scalars once per Newton iteration (the backtracking test); on the GPU everything
// between those reads is captured once as a CUDA graph and replayed.
//
// Supported everywhere: sub-steps, Newton iterations, line search, anchors with paths,
// colliders, Rayleigh damping, plasticity, local and non-local fracture with re-solves,
// retries. The reference's direct solve needs the system in host memory: CPU executor only
// (cudaUnsupportedReason says so).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/fem/collider_kernels.h"
#include "solver/fem/dense_kernels.h"
#include "solver/fem/element_lanes.h"
#include "solver/fracture/cracked_sections.h"
#include "solver/fracture/debris.h"
#include "solver/frame/accelerated_start.h"
#include "solver/frame/contact_term.h"
#include "solver/frame/direct_solver.h"
#include "solver/frame/element_pass.h"
#include "solver/frame/fracture_pass.h"
#include "solver/frame/frame_loop.h"
#include "solver/frame/piece_residual.h"
#include "solver/frame/plastic_state.h"
#include "solver/frame/step.h"
#include "solver/frame/step_backend.h"
#include "solver/frame/timing.h"
#include "solver/multigrid/multigrid_cycle.h"

namespace galsculpt {

// Why a frame with these settings cannot run on the CUDA executor ("" when it can).
inline std::string cudaUnsupportedReason([[maybe_unused]] const SimModel& model,
                                         const StepSettings& s) {
  if (!s.multigrid) return "the reference solver (direct sparse Cholesky) runs on the CPU only";
  return "";
}

template <typename Exec>
class FrameSolver {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  FrameSolver(Exec& ex, const SimModel& model)
      : ex_(ex), model_(model), mg_(ex, model.pattern), contact_(ex, model), plastic_(ex, model) {
    n_ = model.numVertices();
    tets_ = model.numTets();
    edges_ = model.numEdges();
    blocks_ = model.numBlocks();
    // Each block's row, and the index of its transpose partner (c, r) of (r, c): the stiffness
    // is gathered into the blocks on and above the diagonal and mirrored into the others.
    std::vector<int> blockRow(blocks_), transposed(blocks_);
    for (int r = 0; r < n_; ++r)
      for (int k = model.pattern.rowStart[r]; k < model.pattern.rowStart[r + 1]; ++k) {
        blockRow[k] = r;
        transposed[k] = model.pattern.find(model.pattern.columns[k], r);
      }
    blockRow_.adopt(std::move(blockRow));
    transposedBlock_.adopt(std::move(transposed));
    // The model's arrays as they are (read in place on the CPU, copied once to a GPU).
    tetVertices_.mirror(model.tetVertexArray(), 4 * static_cast<size_t>(tets_));
    tetEdges_.mirror(model.tetEdgeArray(), 6 * static_cast<size_t>(tets_));
    rest_.mirror(model.rest);
    mass_.mirror(model.mass);
    rowStart_.mirror(model.pattern.rowStart);
    columns_.mirror(model.pattern.columns);
    diagonal_.mirror(model.pattern.diagonal);
    vertexSlotStart_.mirror(model.vertexSlotStart);
    vertexSlots_.mirror(model.vertexSlots);
    blockSlotStart_.mirror(model.blockSlotStart);
    blockSlots_.mirror(model.blockSlots);
    if (model.fracture.enabled) fracture_ = std::make_unique<FracturePass<Exec>>(ex, model);
    // Every per-vertex buffer up front: nothing may allocate inside a captured section.
    for (Buffer<double>* b :
         {&x_, &v_, &xn_, &vn_, &xhat_, &grad_, &trialGrad_, &acceptedGrad_, &g_, &delta_, &trial_,
          &dampedK_, &tmp_, &savedX_, &savedV_, &pcgB_, &pcgAp_})
      b->resize(3 * n_);
    fixed_.resize(n_);
    removed_.resize(n_);
    damaged_.resize(edges_);
    elemEnergy_.resize(tets_);
    elemInverted_.resize(tets_);
    trialEnergy_.resize(tets_);
    trialInverted_.resize(tets_);
    guardDirty_.resize(tets_);
    for (Buffer<double>* b : {&guardLength_, &potentialAtX_, &potentialAtTrial_}) b->resize(n_);
    guardChanged_.resize(n_);
    stiffnessF_.resize(9 * static_cast<size_t>(tets_));
    stiffnessFresh_.resize(tets_);
    stiffnessOpened_.resize(tets_);
    trialOpened_.resize(tets_);
    elemGrad_.resize(12 * static_cast<size_t>(tets_));
    elemHess_.resize(kPackedHessian * static_cast<size_t>(tets_));
    for (Buffer<double>* b : {&k_, &h_}) b->resize(9 * static_cast<size_t>(blocks_));
    scalars_.resize(kScalars);
    const auto box = boundingBox(model.mesh.vertices);
    modelSize_ = std::max(box.size().norm(), 1e-12);
    double massNorm = 0.0;
    for (double m : model.mass) massNorm += 3.0 * m * m;
    massNorm_ = std::sqrt(massNorm);
  }

  // ---- the state shared with the host (SimState) ------------------------------------------

  // Brings the executor's memory up to date with `state` (uploads only what changed since the
  // last sync; on the CPU executor an upload is a copy).
  void syncIn(const SimState& state, const StepSettings& settings) {
    if (uploadIfChanged(state.x, hostX_, x_)) gradientAtX_ = false;
    uploadIfChanged(state.v, hostV_, v_);
    // Compared by content too: a backend may step several states (tests, undo snapshots).
    const bool damageChanged = hostDamaged_ != state.damaged;
    if (state.damageRevision != damageRevision_ || damageChanged) {
      if (damageChanged) ++hostDamageChanges_;
      hostDamaged_ = state.damaged;
      damaged_.upload(hostDamaged_);
      damageRevision_ = state.damageRevision;
      gradientAtX_ = false;
    }
    if (model_.debrisRemoval > 0.0 && removedFor_ != hostDamageChanges_) {
      removedFor_ = hostDamageChanges_;
      updateRemovedDebris();
      gradientAtX_ = false;
    }
    // Removed debris stays where the state has it (a backend may step several states).
    removedTargets_.clear();
    for (int v : removedVertices_)
      removedTargets_.insert(removedTargets_.end(),
                             {state.x[v].x(), state.x[v].y(), state.x[v].z()});
    if (plastic_.syncIn(state, rest_.data())) gradientAtX_ = false;
    time_ = state.time;
    colliderStates_ = state.colliders;
    for (size_t c = colliderStates_.size(); c < model_.colliders.size(); ++c)
      colliderStates_.push_back(initialColliderState(model_.colliders[c]));
    colliderStates_.resize(model_.colliders.size());
    settings_ = &settings;
    anchors_ = &state.anchors;
    if (settings.multigrid) ensureMultigrid(settings);
    // The stiffness frozen at x_n for damping, kept apart only with several Newton iterations
    // (allocated here: never inside a captured section).
    if (settings.newtonIterations > 1 && frozen_.size() != k_.size()) frozen_.resize(k_.size());
  }

  // Writes positions, velocities, damage and plastic state back (positions through the
  // executor's pinned staging buffer).
  void syncOut(SimState& state) {
    downloadThroughShadow(ex_, x_, hostX_, state.x);
    downloadThroughShadow(ex_, v_, hostV_, state.v);
    if (damageRevision_ != state.damageRevision) {
      state.damaged = hostDamaged_;
      state.damageRevision = damageRevision_;
    }
    plastic_.syncOut(state);
    state.time = time_;
    state.colliders = colliderStates_;
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
    ex_.copy(savedX_.data(), x_.data(), 3 * n_);
    ex_.copy(savedV_.data(), v_.data(), 3 * n_);
    plastic_.save();
    return Saved{time_, colliderStates_};
  }
  // Damage never needs restoring: a failed sub-step is rolled back before its fracture pass,
  // and a fracture re-solve keeps the new damage.
  void restore(const Saved& saved, bool /*keepDamage*/) {
    gradientAtX_ = false;
    ex_.copy(x_.data(), savedX_.data(), 3 * n_);
    ex_.copy(v_.data(), savedV_.data(), 3 * n_);
    plastic_.restore(rest_.data());
    time_ = saved.time;
    colliderStates_ = saved.colliders;
  }

  // ---- kernels ----------------------------------------------------------------------------

  // Energies, forces and (withHessian) stiffnesses of every element at positions y, gathered
  // into `gradient` (3n) and, with the Hessian, into k_. The total energy goes to scalar slot.
  // The number of intact elements turned inside out (det F <= 0) goes to `invertedSlot`: the
  // line search refuses a step that turns more of them than there were.
  // At a trial (not withHessian) the per-element energies and inversions go to trialEnergy_ and
  // trialInverted_, otherwise to elemEnergy_ and elemInverted_. With `only`, just the elements
  // flagged there are evaluated (the vertex guard's rounds); the others keep their last values.
  void elementPass(const double* y, bool withHessian, double* gradient, int energySlot,
                   int invertedSlot, const std::uint8_t* only = nullptr) {
    const ElementInputs in = elementInputs();
    double* energy = withHessian ? elemEnergy_.data() : trialEnergy_.data();
    double* inverted = withHessian ? elemInverted_.data() : trialInverted_.data();
    double* eg = elemGrad_.data();
    double* eh = elemHess_.data();
    const MaterialModel model = model_.material.model;
    const Lame lame = model_.material.lame;
    const bool resists = model_.material.compressionResists;
    const kernels::Hessian mode =
        withHessian ? kernels::Hessian::ProjectedSpd : kernels::Hessian::None;
    // Kept stiffnesses: an element whose deformation gradient moved less than the tolerance
    // (every entry) since its stiffness was evaluated keeps it (its energy and force are new).
    // (beginSubstep marks every record stale: nothing is kept across sub-steps.)
    const double keep = withHessian ? settings_->stiffnessTolerance : 0.0;
    const ElementPass pass{in,
                           y,
                           energy,
                           inverted,
                           eg,
                           eh,
                           model,
                           lame,
                           resists,
                           mode,
                           keep,
                           stiffnessF_.data(),
                           stiffnessFresh_.data(),
                           withHessian ? stiffnessOpened_.data() : trialOpened_.data(),
                           only};
    bool laned = false;
    if constexpr (Exec::kHostMemory) {
      const kernels::LaneBuild build = kernels::chosenLaneBuild();
      // (Without stiffness the damaged elements' lanes were no faster than the scalar kernel:
      // what they take over is mostly the stiffness.)
      const kernels::LaneKernel lanes = withHessian ? kernels::laneKernel(build) : nullptr;
      const kernels::CrackedLaneKernel crackedLanes =
          withHessian ? kernels::crackedLaneKernel(build) : nullptr;
      laned = lanes != nullptr || crackedLanes != nullptr;
      if (laned) elementPassInLanes(ex_, pass, tets_, lanes, crackedLanes);
    }
    if (!laned)
      ex_.forEach(tets_, [=] GALSCULPT_LAMBDA(int t) {
        double x12[12];
        std::uint8_t intact;
        const kernels::RestData* r;
        kernels::Hessian elementMode;
        if (pass.prepare(t, x12, intact, r, elementMode))
          pass.evaluate(t, x12, intact, *r, elementMode);
      });
    const std::uint8_t* fresh = stiffnessFresh_.data();
    if (keep > 0.0)
      ex_.sum(
          tets_, [=] GALSCULPT_LAMBDA(int t) { return fresh[t] ? 0.0 : 1.0; },
          scalars_.data() + kKept);
    ex_.sum(
        tets_, [=] GALSCULPT_LAMBDA(int t) { return energy[t]; }, scalars_.data() + energySlot);
    ex_.sum(
        tets_, [=] GALSCULPT_LAMBDA(int t) { return inverted[t]; }, scalars_.data() + invertedSlot);
    if (!withHessian && settings_->reuseStiffness) {
      // The damaged elements whose open cracks differ from where the stiffness was evaluated.
      const std::uint8_t* atStiffness = stiffnessOpened_.data();
      const std::uint8_t* atTrial = trialOpened_.data();
      ex_.sum(
          tets_, [=] GALSCULPT_LAMBDA(int t) { return atStiffness[t] != atTrial[t] ? 1.0 : 0.0; },
          scalars_.data() + kSwitched);
    }
    const int* vStart = vertexSlotStart_.data();
    const int* vSlots = vertexSlots_.data();
    ex_.forEach(n_, [=] GALSCULPT_LAMBDA(int v) {
      double acc[3] = {0.0, 0.0, 0.0};
      for (int i = vStart[v]; i < vStart[v + 1]; ++i) {
        const int slot = vSlots[i], t = slot / 4, a = slot % 4;
        for (int k = 0; k < 3; ++k) acc[k] += eg[12 * t + 3 * a + k];
      }
      for (int k = 0; k < 3; ++k) gradient[3 * v + k] = acc[k];
    });
    if (!withHessian) return;
    const int* bStart = blockSlotStart_.data();
    const int* bSlots = blockSlots_.data();
    double* kb = k_.data();
    const std::uint8_t* freshOnly = keep > 0.0 ? fresh : nullptr;
    const int* blockRow = blockRow_.data();
    const int* columns = columns_.data();
    const int* transposed = transposedBlock_.data();
    const std::uint8_t* opened = stiffnessOpened_.data();
    // The blocks on and above the diagonal from the elements' packed upper blocks, then those
    // below as their partners' transposes: an element's stiffness is read once, not its six
    // lower blocks again (the gather reads scattered elements: a sixth of a 100-cut frame).
    ex_.forEach(blocks_, [=] GALSCULPT_LAMBDA(int b) {
      if (blockRow[b] > columns[b]) return;
      if (freshOnly) {  // a block of kept stiffnesses only is what it was
        bool any = false;
        for (int i = bStart[b]; i < bStart[b + 1] && !any; ++i) any = freshOnly[bSlots[i] / 16];
        if (!any) return;
      }
      double acc[9] = {};
      for (int i = bStart[b]; i < bStart[b + 1]; ++i) {
        const int slot = bSlots[i], t = slot / 16, a = (slot % 16) / 4, c = slot % 4;
        // Zero and not written (adding its zeros would leave the sums' bits as they are).
        if (ElementPass::zeroStiffness(opened[t])) continue;
        const double* h = eh + kPackedHessian * static_cast<size_t>(t);
        if (a <= c) {
          const double* blk = h + 9 * packedBlock(a, c);
          for (int k = 0; k < 9; ++k) acc[k] += blk[k];
        } else {  // the mirror of block (c, a)
          const double* blk = h + 9 * packedBlock(c, a);
          for (int j = 0; j < 3; ++j)
            for (int r = 0; r < 3; ++r) acc[r + 3 * j] += blk[j + 3 * r];
        }
      }
      for (int i = 0; i < 9; ++i) kb[9 * b + i] = acc[i];
    });
    ex_.forEach(blocks_, [=] GALSCULPT_LAMBDA(int b) {
      if (blockRow[b] <= columns[b]) return;
      const double* upper = kb + 9 * static_cast<size_t>(transposed[b]);
      for (int j = 0; j < 3; ++j)
        for (int r = 0; r < 3; ++r) kb[9 * b + r + 3 * j] = upper[j + 3 * r];
    });
  }

  static constexpr int kPackedHessian = ElementPass::kPackedHessian;
  GALSCULPT_HD static int packedBlock(int a, int c) { return ElementPass::packedBlock(a, c); }

  ElementInputs elementInputs() const {
    return {tetVertices_.data(), tetEdges_.data(),  damaged_.data(), rest_.data(),
            plastic_.shapes(),   plastic_.shaped(), removed_.data()};
  }

  // out = beta K0 (y - x_n).
  void dampedProduct(const double* y, double* out) {
    const double* xn = xn_.data();
    const double* frozen = frozenBlocks();
    const int* rowStart = rowStart_.data();
    const int* columns = columns_.data();
    const double beta = model_.material.dampingStiffness;
    ex_.forEach(n_, [=] GALSCULPT_LAMBDA(int r) {
      double acc[3] = {0.0, 0.0, 0.0};
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
        const int c = columns[k];
        const double d[3] = {y[3 * c] - xn[3 * c], y[3 * c + 1] - xn[3 * c + 1],
                             y[3 * c + 2] - xn[3 * c + 2]};
        double t[3];
        multiply3(frozen + 9 * k, d, t);
        for (int i = 0; i < 3; ++i) acc[i] += t[i];
      }
      for (int i = 0; i < 3; ++i) out[3 * r + i] = beta * acc[i];
    });
  }

  // Penalty contact at y: energy into a slot; gradient added (when given).
  void contact(const double* y, double* gradient, int energySlot) {
    contact_.energy(y, fixed_.data(), mass_.data(), h_step_, gradient,
                    scalars_.data() + energySlot);
  }

  // The terms of the incremental potential that belong to one coordinate: inertia, gravity and
  // damping (dampedK: beta K0 (y - x_n)).
  struct DofPotential {
    const double *xhat, *xn, *mass;
    double h, alpha, gravity[3];
    GALSCULPT_HD double operator()(int i, const double* y, const double* dampedK) const {
      const double m = mass[i / 3];
      const double g = gravity[i % 3];
      const double inertia = y[i] - xhat[i], dx = y[i] - xn[i];
      return 0.5 / (h * h) * inertia * (m * inertia) - m * g * y[i] +
             0.5 / h * (alpha * dx * (m * dx) + dx * dampedK[i]);
    }
  };
  DofPotential dofPotential() const {
    return {xhat_.data(),
            xn_.data(),
            mass_.data(),
            h_step_,
            model_.material.dampingMass,
            {model_.gravity.x(), model_.gravity.y(), model_.gravity.z()}};
  }

  // The incremental potential at y (elastic and contact energies in slots) into a slot.
  void objective(const double* y, int elasticSlot, int contactSlot, const double* dampedK,
                 int outSlot) {
    const DofPotential dof = dofPotential();
    double* sc = scalars_.data();
    ex_.sum(
        3 * n_, [=] GALSCULPT_LAMBDA(int i) { return dof(i, y, dampedK); }, sc + outSlot);
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc[outSlot] += sc[elasticSlot] + sc[contactSlot]; });
  }

  // Each vertex's share of the incremental potential at y: a quarter of each element energy
  // around it, its own inertia, gravity, damping and contact terms (they sum to the potential).
  // `energy`: the elements' energies at y; the contact term's must be y's.
  void vertexPotential(const double* y, const double* energy, const double* dampedK, double* out) {
    const DofPotential dof = dofPotential();
    const int* vStart = vertexSlotStart_.data();
    const int* vSlots = vertexSlots_.data();
    const double* contactEnergy = contact_.perVertex();
    ex_.forEach(n_, [=] GALSCULPT_LAMBDA(int v) {
      double sum = contactEnergy ? contactEnergy[v] : 0.0;
      for (int i = vStart[v]; i < vStart[v + 1]; ++i) sum += 0.25 * energy[vSlots[i] / 4];
      for (int k = 0; k < 3; ++k) sum += dof(3 * v + k, y, dampedK);
      out[v] = sum;
    });
  }

  // g = M (y - xhat)/h^2 + grad - f_ext + (alpha M dx + dampedK)/h (+ contact, already in
  // grad), zero on anchored vertices.
  void backwardEulerGradient(const double* y, const double* grad, const double* dampedK,
                             double* g) {
    const double* xhat = xhat_.data();
    const double* xn = xn_.data();
    const double* mass = mass_.data();
    const std::uint8_t* fixed = fixed_.data();
    const double h = h_step_;
    const double alpha = model_.material.dampingMass;
    const double gx = model_.gravity.x(), gy = model_.gravity.y(), gz = model_.gravity.z();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) {
      if (fixed[i / 3]) {
        g[i] = 0.0;
        return;
      }
      const double m = mass[i / 3];
      const double gravity = i % 3 == 0 ? gx : (i % 3 == 1 ? gy : gz);
      g[i] = m * (y[i] - xhat[i]) / (h * h) + grad[i] - m * gravity +
             (alpha * (m * (y[i] - xn[i])) + dampedK[i]) / h;
    });
  }

  // H = K + beta/h K0 + contact + M (1/h^2 + alpha/h), anchored rows and columns identity-scaled.
  void buildSystem(const double* y) {
    const double* kb = k_.data();
    const double* frozen = frozenBlocks();
    double* hb = h_.data();
    const int* blockRow = blockRow_.data();
    const int* columns = columns_.data();
    const std::uint8_t* fixed = fixed_.data();
    const double* mass = mass_.data();
    const double h = h_step_;
    const auto contactStiffness = contact_.stiffness(mass, h);
    const double betaOverH = model_.material.dampingStiffness / h;
    const double alpha = model_.material.dampingMass;
    ex_.forEach(blocks_, [=] GALSCULPT_LAMBDA(int b) {
      const int r = blockRow[b], c = columns[b];
      double out[9];
      for (int i = 0; i < 9; ++i) out[i] = kb[9 * b + i] + betaOverH * frozen[9 * b + i];
      if (r == c) {
        if (!fixed[r]) contactStiffness.add(r, y, out);
        const double m = mass[r] * (1.0 / (h * h) + alpha / h);
        for (int i = 0; i < 3; ++i) out[4 * i] += m;
      }
      if (fixed[r] || fixed[c]) {
        const double diag = r == c ? mass[r] / (h * h) : 0.0;
        for (int i = 0; i < 9; ++i) out[i] = i % 4 == 0 ? diag : 0.0;
      }
      for (int i = 0; i < 9; ++i) hb[9 * b + i] = out[i];
    });
  }

  // ---- one backward-Euler sub-step ----------------------------------------------------------

  // Newton iterations until the residual is within the tolerance (converged), Newton's step
  // test is met, the iterations are spent or the frame's time budget is (not converged).
  SubstepOutcome substep(double h) {
    const StepSettings& s = *settings_;
    SubstepOutcome result;
    beginSubstep(h);
    bool stationary = false;
    bool reuse = false;  // solve with the last iteration's stiffness (a chord step)
    bool chordFailed = false;
    double lastResidual = 0.0;
    for (int it = 0; it < s.newtonIterations; ++it) {
      const NewtonOutcome n = newtonIteration(h, it, reuse, result);
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
      if (s.residualTolerance <= 0.0 && !s.reuseStiffness) continue;  // nothing reads it
      const double residual = residualAt();
      if (residual <= s.residualTolerance && piecesWithinTolerance(residual, tmp_.data())) break;
      // Keep the stiffness while it still cuts the residual at least in half. Once a chord step
      // has not, the stiffness moves with the iterate (cracks opening and closing, contacts
      // coming and going): every later iteration of the sub-step takes a fresh one, since
      // alternating fresh and chord steps there wastes every other iteration and the chords'
      // poor steps cost backtracks (docs/benchmarks.md has the measurements).
      chordFailed = chordFailed || (reuse && !(residual < 0.5 * lastResidual));
      // Nor is a chord taken after a step that opened or closed cracks in more than
      // kChordSwitchedElements elements: each such element's stiffness is another matrix (a
      // closed crack's edge carries the faces' contact, an open one nothing), and the chord steps
      // with the wrong one. Where only a few elements switch, chords still pay as often as not
      // (docs/benchmarks.md).
      reuse = s.reuseStiffness && !chordFailed && switchedCracks_ <= kChordSwitchedElements &&
              !systemSkipped_;
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
    result.cgIterations = pcgIterations_;
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
  // tolerance of its own loads at the accepted positions (g_ and tmp_, from residualAt();
  // `residual` the body's there). The body's residual is one 2-norm and a small piece's share of
  // it is small, so a solve to the body's target leaves such a piece where it is: a first
  // prototype of this criterion iterated to its 40 Newton iterations, null steps nearly all
  // (docs/benchmarks.md). A piece above its tolerance by a factor R therefore caps PCG's
  // absolute target (and the null step's) for the rest of the sub-step at 0.5 / R of the body's
  // residual or of the body's own target, whichever is smaller: an inexact Newton forcing term
  // set by the worst piece, below the residual so that a solve always has something to do
  // (capped at the body's target only, a body at rest with its residual already far below it
  // took null steps to the 40 iterations).
  // `forces`: the elastic and contact forces beside g_ (tmp_ there; grad_ in newtonStep).
  bool piecesWithinTolerance(double residual, const double* forces) {
    const StepSettings& s = *settings_;
    if (!s.convergePieces) return true;
    const double worst = pieceResidual_.measure(ex_, pieces(), g_.data(), forces, fixed_.data(),
                                                mass_.data(), model_.gravity.norm());
    if (worst <= s.residualTolerance) return true;  // (-1: fewer than two measured pieces)
    const double share = 0.5 * s.residualTolerance / worst;
    pieceTargetCap_ =
        std::min(pieceTargetCap_, share * std::min(residual, 0.5 * s.residualTolerance) *
                                      std::max(weight(), forceScale_));
    return false;
  }

  // The backward-Euler residual at the accepted positions over the force scale (one read).
  double residualAt() {
    acceptedResidual();
    double read[kScalars];
    ex_.read(scalars_.data(), read, kScalars);
    return relativeResidual(read);
  }

  // The backward-Euler gradient at the accepted positions (g_; the elastic and contact forces in
  // tmp_) and its sums (residualSums).
  void acceptedResidual() {
    const double* x = x_.data();
    dampedProduct(x, dampedK_.data());
    ex_.copy(tmp_.data(), acceptedGrad_.data(), 3 * n_);
    contact(x, tmp_.data(), kContact);
    backwardEulerGradient(x, tmp_.data(), dampedK_.data(), g_.data());
    residualSums();
  }

  // |g|^2 (kResidual) and the squared elastic and contact forces on the free vertices
  // (kForceScale), from g_ and tmp_.
  void residualSums() {
    const double* g = g_.data();
    const double* f = tmp_.data();
    const std::uint8_t* fixed = fixed_.data();
    double* sc = scalars_.data();
    ex_.sum(
        3 * n_, [=] GALSCULPT_LAMBDA(int i) { return g[i] * g[i]; }, sc + kResidual);
    ex_.sum(
        3 * n_, [=] GALSCULPT_LAMBDA(int i) { return fixed[i / 3] ? 0.0 : f[i] * f[i]; },
        sc + kForceScale);
  }

  // The residual over the force scale: the larger of the body's weight and the elastic and
  // contact forces acting on it, so that a frame is solved to the same fraction of its loads
  // whether it hangs under gravity or takes a striker's meganewtons.
  double relativeResidual(const double* read) {
    forceScale_ = std::max(weight(), std::sqrt(read[kForceScale]));
    return std::sqrt(read[kResidual]) / forceScale_;
  }

  // |f_ext| = |g| |m| over the vertices (massNorm_ is over the 3n DOFs: |m| sqrt 3), at least 1 g.
  double weight() const {
    const double perDofMass = massNorm_ / std::sqrt(3.0);
    return std::max(model_.gravity.norm() * perDofMass, 9.81 * perDofMass);
  }

  // x_n, v_n and the inertial target from the state; anchored vertices on their paths.
  void beginSubstep(double h) {
    h_step_ = h;
    pieceTargetCap_ = std::numeric_limits<double>::infinity();
    pcgIterations_ = 0;
    prepareAnchorsAndColliders(time_ + h, h);
    double* x = x_.data();
    double* v = v_.data();
    double* xn = xn_.data();
    double* vn = vn_.data();
    double* xhat = xhat_.data();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) {
      xn[i] = x[i];
      vn[i] = v[i];
      xhat[i] = x[i] + h * v[i];
    });
    const bool gradientAtXn = gradientAtX_;
    gradientAtX_ = false;  // x moves on from x_n below
    predicted_ = settings_->predictedStart;
    if (predicted_) {
      ex_.copy(x, xhat, 3 * n_);
      if (settings_->acceleratedStart) startPiecesAccelerated(h, gradientAtXn);
    }
    // Stiffnesses are kept within a sub-step only: a frame's result must follow from the state
    // alone, so that a project reopened at any frame runs on identically (stiffnesses kept across
    // frames are not part of the saved state). This also
    // covers everything that changes a rest shape (plastic flow, a rolled-back or uploaded
    // plastic state): it happens between sub-steps.
    if (settings_->stiffnessTolerance > 0.0) {
      double* keptF = stiffnessF_.data();
      const double nan = std::numeric_limits<double>::quiet_NaN();
      ex_.forEach(tets_, [=] GALSCULPT_LAMBDA(int t) { keptF[9 * t] = nan; });
    }
    placeAnchors();
    frozenIsK_ = true;
  }

  // Pieces nothing holds start on their path with their acceleration (accelerated_start.h).
  // Called after prepareAnchorsAndColliders (fixed_ and the poses are the sub-step's).
  void startPiecesAccelerated(double h, bool gradientAtXn) {
    const ElementInputs in = elementInputs();
    const MaterialModel model = model_.material.model;
    const Lame lame = model_.material.lame;
    const bool resists = model_.material.compressionResists;
    const auto elementGradient = [=] GALSCULPT_LAMBDA(int t, const double* y, double* gradient) {
      double x12[12], energy;
      std::uint8_t intact;
      const kernels::RestData& r = in.load(t, y, x12, intact);
      kernels::evaluateElement(model, lame, r, x12, intact, in.resists(t, resists),
                               kernels::Hessian::None, energy, gradient, nullptr);
    };
    const typename AcceleratedStart<Exec>::SubstepInputs inputs{
        anchorCount_ > 0,
        fixed_.data(),
        removed_.data(),
        xn_.data(),
        xhat_.data(),
        vn_.data(),
        mass_.data(),
        contact_.poses(),
        contact_.colliders(),
        h,
        model_.material.dampingMass,
        {model_.gravity.x(), model_.gravity.y(), model_.gravity.z()}};
    // Copied on the host executor only: its element kernel is compiled without contracted
    // multiply-adds, so the copy is the evaluation bit for bit and a frame still follows from
    // the state alone. nvcc contracts them as each kernel's inlining allows, so on the GPU the
    // two could differ in their last bits; there the elements are evaluated, in parallel.
    const bool copy = gradientAtXn && Exec::kHostMemory;
    accelerated_.start(ex_, model_, pieces(), inputs, elementGradient,
                       copy ? elemGrad_.data() : nullptr, x_.data());
  }

  // The pieces of the current damage (host), counted once per damage change for all that reads
  // them: the debris rule, the pieces' start and the residual piece by piece.
  const PieceCensus& census() {
    if (censusFor_ != hostDamageChanges_) {
      census_ = censusPieces(model_, hostDamaged_);
      censusFor_ = hostDamageChanges_;
    }
    return census_;
  }
  const PieceLayout& pieces() {
    if (piecesFor_ != hostDamageChanges_) {
      pieces_ = pieceLayout(model_, census(), hostDamaged_, pieces_.revision + 1);
      piecesFor_ = hostDamageChanges_;
    }
    return pieces_;
  }

  // Anchored vertices on their paths at the sub-step's end.
  void placeAnchors() {
    double* x = x_.data();
    const int* anchorVertex = anchorVertices_.data();
    const double* anchorTarget = anchorTargets_.data();
    ex_.forEach(static_cast<int>(anchorCount_), [=] GALSCULPT_LAMBDA(int i) {
      for (int k = 0; k < 3; ++k) x[3 * anchorVertex[i] + k] = anchorTarget[3 * i + k];
    });
  }

  // Newton starts from x_n when the prediction x_n + h v_n turned an intact element inside out
  // (the line search only refuses steps that invert more: it would keep those). `read`: the
  // scalars after the first Newton step.
  bool dropInvertingPrediction(const double* read) {
    if (!predicted_) return false;
    predicted_ = false;
    if (!(read[kInverted] > 0.0)) return false;
    ex_.copy(x_.data(), xn_.data(), 3 * n_);
    placeAnchors();
    return true;
  }

  // Converged: the step was below Newton's step test; Stalled: no step length descends (a
  // failure before any progress, else the end of the iterations, converged only if the
  // residual says so).
  // Restart: the predicted start was dropped, the iteration runs again from x_n.
  enum class NewtonOutcome { Continue, Converged, Stalled, Failed, Restart };

  // One Newton iteration: the step (assembled, solved, measured, its full length tried),
  // shortened while it raises the incremental potential, then accepted.
  NewtonOutcome newtonIteration(double h, int it, bool reuse, SubstepOutcome& result) {
    const StepSettings& s = *settings_;
    const auto t0 = Clock::now();
    const double elementsBefore = result.msElements;
    gradientAtX_ = false;  // the element passes below overwrite elemGrad_
    // Structural changes first (host): the hierarchy follows the damage.
    if (s.multigrid && s.multigridSettings.splitAggregates &&
        multigrid_->updateDamage(model_.edges, hostDamaged_, damageRevision_)) {
      mg_.upload(buildMultigridLayout(*multigrid_, model_.pattern));
      ++mgRevision_;
    }
    // The Newton step and its full-length trial: launches only, captured as one graph and
    // replayed, unless a dense Cholesky, PCG or the direct solve needs host reads in between.
    const bool capturable =
        s.multigrid && !s.multigridSettings.coarseCholesky && !s.multigridSettings.pcg;
    if (capturable) {
      ex_.captured(0, graphKey(h, it) ^ (reuse ? 0x9e3779b97f4a7c15ull : 0),
                   [&] { newtonStep(it, reuse, result); });
    } else {
      newtonStep(it, reuse, result);
    }
    double read[kScalars];
    ex_.read(scalars_.data(), read, kScalars);
    if (it == 0 && dropInvertingPrediction(read)) {
      result.msSolve += msSince(t0);
      if constexpr (Exec::kHostMemory) result.msSolve -= result.msElements - elementsBefore;
      return NewtonOutcome::Restart;
    }
    ++result.iterations;
    if (!reuse && s.stiffnessTolerance > 0.0) result.keptStiffnesses += read[kKept];
    const double stepLength = lineSearch(result, read);
    switchedCracks_ = s.reuseStiffness ? read[kSwitched] : 0.0;
    result.msSolve += msSince(t0);
    if constexpr (Exec::kHostMemory) result.msSolve -= result.msElements - elementsBefore;
    if (stepLength < 0.0) return NewtonOutcome::Failed;
    if (stepLength < kShortestStep)  // no descent: a failure only before any progress
      return result.iterations == 1 ? NewtonOutcome::Failed : NewtonOutcome::Stalled;
    // Accept: the trial just evaluated is the new iterate (its energy and gradient too).
    ex_.copy(x_.data(), trial_.data(), 3 * n_);
    ex_.copy(acceptedGrad_.data(), trialGrad_.data(), 3 * n_);
    ex_.copy(elemEnergy_.data(), trialEnergy_.data(), tets_);
    ex_.copy(elemInverted_.data(), trialInverted_.data(), tets_);
    gradientAtX_ = true;  // the line search's last trial is the accepted one
    result.energy = read[kTrialElastic];
    // Newton's step test on the full step: a step shortened to nothing says nothing about
    // stationarity (it once flagged the human figure's frozen frames as converged).
    return read[kDeltaMax] < s.tolerance * modelSize_ ? NewtonOutcome::Converged
                                                      : NewtonOutcome::Continue;
  }

  // Assembles and solves the Newton system at x, measures the step and tries its full length.
  // With `reuse`, the system (stiffness, contact, the multigrid's operators) stays the last
  // iteration's and only the gradient is new: the accepted trial's, already evaluated.
  void newtonStep(int it, bool reuse, SubstepOutcome& result) {
    const StepSettings& s = *settings_;
    const double* x = x_.data();
    if (reuse) {
      ex_.copy(grad_.data(), acceptedGrad_.data(), 3 * n_);
      double* sc = scalars_.data();
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
        sc[kElastic] = sc[kTrialElastic];
        sc[kInverted] = sc[kTrialInverted];
      });
    } else {
      const bool frozenCopy = it == 0 && s.newtonIterations > 1;
      const auto tElements = Clock::now();
      elementPass(x, true, grad_.data(), kElastic, kInverted);
      // Phases are timed where launches run as they are issued (the CPU); on the GPU they run
      // as one graph and all of it counts as solve.
      if constexpr (Exec::kHostMemory) result.msElements += msSince(tElements);
      if (frozenCopy) ex_.copy(frozen_.data(), k_.data(), k_.size());
      frozenIsK_ = !(frozenCopy || (it > 0 && s.newtonIterations > 1));
    }
    // Under PCG a fresh iteration may find the gradient already within the solve's target: the
    // step is null, and nothing past the gradient is needed (takeNullStep).
    const bool mayBeNull = !reuse && s.multigrid && s.multigridSettings.pcg && s.skipNullSolves;
    contact(x, grad_.data(), kContact);
    dampedProduct(x, dampedK_.data());
    backwardEulerGradient(x, grad_.data(), dampedK_.data(), g_.data());
    double bodyResidual = 0.0;
    // A null step for the body is none for a piece still above its own tolerance: it sets the
    // cap, and this iteration solves (a settled body can hide a piece that still spins).
    if (mayBeNull && nullStep(bodyResidual) && piecesWithinTolerance(bodyResidual, grad_.data())) {
      takeNullStep();
      return;
    }
    systemSkipped_ = false;
    if (!reuse) buildSystem(x);
    if (s.multigrid) {
      if (!reuse) {
        mg_.setFixed(fixed_.data());
        // Under PCG the V-cycle only preconditions: its smoother may read floats.
        mg_.refresh(h_.data(), s.multigridSettings.coarseCholesky, s.multigridSettings.pcg);
      }
      solveLinear();
    } else {
      solveDirect();
    }
    stepMeasures();
    evaluateTrial(1.0);
  }

  // Whether PCG would return the null step: |b| = |g| (all 3n entries, as PCG reads them) within
  // its target (solveLinear, MultigridCycle::pcg), which it checks before its first iteration
  // (but after a V-cycle). One host read, where PCG makes several. When null, `bodyResidual` is
  // the body's relative residual there (|g| over the last force scale).
  bool nullStep(double& bodyResidual) {
    const StepSettings& s = *settings_;
    const double* g = g_.data();
    double* sc = scalars_.data();
    ex_.sum(
        3 * n_, [=] GALSCULPT_LAMBDA(int i) { return g[i] * g[i]; }, sc + kR0);
    double r0 = 0.0;
    ex_.read(sc + kR0, &r0, 1);
    const double bnorm = std::sqrt(r0);
    const double target =
        std::max(s.multigridSettings.pcgTolerance * std::max(bnorm, 1e-300), pcgTarget());
    if (bnorm > target) return false;
    pcgReduction_ = bnorm > 0.0 ? 1.0 : 0.0;  // what PCG returns after no iteration
    bodyResidual = bnorm / std::max(weight(), forceScale_);
    return true;
  }

  // The null step, taken without what it would not use: the system, the multigrid's operators
  // and PCG's first V-cycle. Its trial (at x) is still evaluated: the trial's element pass is
  // the one whose energies and gradients the frame reports and the next sub-step's start reads,
  // and the stiffness pass's (SIMD lanes) may differ from them in the last bits, which a frame
  // that follows from the state alone cannot allow. At rest most frames are one null step.
  // The system was not built: the next iteration of the sub-step takes a fresh one.
  void takeNullStep() {
    double* delta = delta_.data();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) { delta[i] = 0.0; });
    stepMeasures();
    evaluateTrial(1.0);
    systemSkipped_ = true;
  }

  // Whether the trial at `length` (its scalars in `read`) lowers the potential enough: Armijo
  // with `sufficient`, up to the sums' round-off.
  static bool descent(const double* read, double length, double sufficient) {
    const double e0 = read[kE0], e1 = read[kE1];
    return std::isfinite(e1) &&
           e1 <= e0 + sufficient * length * read[kSlope] + 1e-12 * std::abs(e0);
  }

  // A shortened step at which the potential still falls at least half as steeply as the slope
  // says is doubled while the potential keeps falling, short of the refused length; the trial
  // evaluated last is the accepted one's. The quadratic fit through a refused length puts the
  // minimum far too short where the potential kinks instead of curving: a step that closes a
  // body's cracks (or opens them) rises steeply past the switch, and backtracking took a tenth
  // of the step each iteration (two halves of a cut slab driven together: 18 Newton iterations
  // in the impact frame, 9 with this).
  double lengthened(SubstepOutcome& result, double* read, double length, double refused,
                    double sufficient) {
    double best = length, bestEnergy = read[kE1];
    const double inverted = read[kInverted];
    while (read[kE1] - read[kE0] <= 0.5 * best * read[kSlope] && 2.0 * best < refused) {
      evaluateTrial(2.0 * best);
      result.energyPasses += 1.0;
      ex_.read(scalars_.data(), read, kScalars);
      const bool better = !(read[kBad] > 0.0) && descent(read, 2.0 * best, sufficient) &&
                          read[kE1] < bestEnergy && read[kTrialInverted] <= inverted;
      if (!better) {
        evaluateTrial(best);
        result.energyPasses += 1.0;
        ex_.read(scalars_.data(), read, kScalars);
        return best;
      }
      best *= 2.0;
      bestEnergy = read[kE1];
    }
    return best;
  }

  // A chord step is taken while at most this many elements changed their open cracks since the
  // stiffness was evaluated (substep). A count, not a share of the body: what a switched element
  // gets wrong in the chord's step is local to it.
  static constexpr double kChordSwitchedElements = 64;
  static constexpr double kShortestStep = 1e-8;
  // Shorter than this, a step refused only for turning elements inside out is taken anyway
  // (after the lengths 1, 1/2, 1/4 all inverted: on the human figure giving up at 1e-3 instead
  // cost twice the Newton iterations for the same frames).
  static constexpr double kInversionGiveUp = 1e-2;

  // Backtracking on the step evaluated at full length (`read`: its scalars, already read):
  // shortens it (shorterStep) until the potential drops (Armijo with the line search, plain
  // decrease without) without turning more intact elements inside out. Returns the accepted
  // length, something under kShortestStep when none descends, or -1 for NaN; `read` holds the
  // scalars of the last trial.
  double lineSearch(SubstepOutcome& result, double* read) {
    const StepSettings& s = *settings_;
    const double sufficient = s.lineSearch ? 1e-4 : 0.0;
    double stepLength = 1.0;
    double inverting = 0.0;  // the longest length refused only because it inverted elements
    double refused = 0.0;    // the shortest length refused so far (0: none)
    bool guarded = !s.vertexGuard, folded = false;
    for (;; ex_.read(scalars_.data(), read, kScalars)) {
      if (stepLength == 1.0)
        result.linearResidualReduction =
            s.multigridSettings.pcg ? pcgReduction_
                                    : (read[kR0] > 0.0 ? std::sqrt(read[kR1] / read[kR0]) : 0.0);
      if (read[kBad] > 0.0 || !std::isfinite(read[kElastic])) return -1.0;
      // A null step (the linear solve had nothing to do: the gradient was already within its
      // target) moves nothing and is taken. Judged by the energy it could be refused: e0 and e1
      // are sums whose round-off (a cracked element's energy is a difference of its strains and
      // openings) exceeds 1e-12 of a nearly stress-free body's tiny potential, and refusing it at
      // every length failed the sub-step, every retry, and froze the body.
      if (read[kDeltaMax] == 0.0) return stepLength;
      const double e0 = read[kE0], e1 = read[kE1];
      // A step that turns more elements inside out is shortened (under extreme loads the energy
      // alone may descend through an inversion), down to kInversionGiveUp (below).
      const bool descends = descent(read, stepLength, sufficient);
      if (descends && read[kTrialInverted] <= read[kInverted])
        return refused > 0.0 && !folded ? lengthened(result, read, stepLength, refused, sufficient)
                                        : stepLength;
      if (descends && inverting == 0.0) inverting = stepLength;
      if (!guarded) {  // the full step failed: shorten it only where the potential rose
        guarded = true;
        double full[kScalars];
        std::copy(read, read + kScalars, full);
        if (vertexGuard(result, read)) return 1.0;
        if (read[kGuardSlope] < 0.0 && std::isfinite(read[kE1])) {
          // Back off the guarded step as a whole: it is the step from here on.
          foldGuardIntoStep();
          inverting = 0.0;
          folded = true;
          continue;
        }
        std::copy(full, full + kScalars, read);  // back to shortening the whole full step
      }
      refused = stepLength;
      stepLength = shorterStep(stepLength, e0, e1, read);
      ++result.backtracks;
      // An element on the edge of inversion that the solution turns over (a sliver, a plastic
      // rest shape) refuses every length: rather than freezing the body (the human figure stood
      // still from frame 21 on), take the descending step; the frame reports the elements it
      // leaves inside out (a warning).
      if (stepLength < kInversionGiveUp && inverting > 0.0) {
        evaluateTrial(inverting);
        result.energyPasses += 1.0;
        ex_.read(scalars_.data(), read, kScalars);
        return inverting;
      }
      if (stepLength < kShortestStep) return stepLength;
      evaluateTrial(stepLength);
      result.energyPasses += 1.0;
    }
  }

  static constexpr int kGuardRounds = 6;
  static constexpr int kGuardLevels = 24;  // thresholds tried: the excess times 2^-k

  // The vertex guard (StepSettings::vertexGuard), after the full step raised the potential or
  // turned elements inside out. Each round, the vertices whose share of the potential rose the
  // most (the fewest whose rises add up to twice the excess over the accepted decrease, found
  // among thresholds excess 2^-k, or nine tenths of all rises where they add up to less) and those
  // of elements the trial turned over shorten their own steps: to the minimum of the quadratic
  // through their share at x, their slope and their share at the trial, kept within a tenth and a
  // half of their length. Only the elements around them are evaluated again. (A vertex's share may
  // rise in a good step, its neighbours' falling more: shortening every vertex whose share rose
  // would hold back large parts of a body that moves well.) True when a trial descends (Armijo on
  // the shortened step's slope) without turning more elements over: trial_ and its scalars (`read`)
  // are then the accepted step. False leaves the caller to back off the whole step.
  bool vertexGuard(SubstepOutcome& result, double* read) {
    const double sufficient = settings_->lineSearch ? 1e-4 : 0.0;
    double* length = guardLength_.data();
    double* rise = potentialAtTrial_.data();  // the trial's shares, then their rises
    const double* atX = potentialAtX_.data();
    std::uint8_t* changed = guardChanged_.data();
    std::uint8_t* dirty = guardDirty_.data();
    const std::uint8_t* fixed = fixed_.data();
    const double* g = g_.data();
    const double* delta = delta_.data();
    const double* x = x_.data();
    double* trial = trial_.data();
    const double* invertedAtX = elemInverted_.data();
    const double* invertedAtTrial = trialInverted_.data();
    const int* vStart = vertexSlotStart_.data();
    const int* vSlots = vertexSlots_.data();
    const int* tv = tetVertices_.data();
    double* sc = scalars_.data();
    ex_.forEach(n_, [=] GALSCULPT_LAMBDA(int v) { length[v] = 1.0; });
    read[kGuardSlope] = read[kSlope];  // the full step's
    for (int round = 0; round < kGuardRounds; ++round) {
      // The rises (0 where the vertex cannot move) and, in `changed`, who the trial turned over.
      vertexPotential(trial, trialEnergy_.data(), tmp_.data(), rise);
      ex_.forEach(n_, [=] GALSCULPT_LAMBDA(int v) {
        bool turned = false;
        for (int i = vStart[v]; i < vStart[v + 1] && !turned; ++i)
          turned = invertedAtTrial[vSlots[i] / 4] > invertedAtX[vSlots[i] / 4];
        const bool moves = !fixed[v] && length[v] > 0.0;
        changed[v] = moves && turned;
        rise[v] = moves ? fmax(rise[v] - atX[v], 0.0) : 0.0;
      });
      const double excess =
          read[kE1] - read[kE0] - sufficient * read[kGuardSlope] - 1e-12 * std::abs(read[kE0]);
      double threshold = std::numeric_limits<double>::infinity();  // only the turned over
      if (excess > 0.0) {
        for (int k = 0; k < kGuardLevels; ++k) {
          const double level = std::ldexp(excess, -k);
          ex_.sum(
              n_, [=] GALSCULPT_LAMBDA(int v) { return rise[v] > level ? rise[v] : 0.0; },
              sc + kGuardLevel + k);
        }
        ex_.sum(
            n_, [=] GALSCULPT_LAMBDA(int v) { return rise[v]; }, sc + kGuardLevel + kGuardLevels);
        double levels[kGuardLevels + 1];
        ex_.read(sc + kGuardLevel, levels, kGuardLevels + 1);
        // Twice the excess, or nine tenths of all the rises where they add up to less (a rise
        // concentrated on one element's four vertices is about the excess itself).
        const double wanted = std::min(2.0 * excess, 0.9 * levels[kGuardLevels]);
        threshold = 0.0;  // every rise, if no level gathers enough
        for (int k = 0; k < kGuardLevels; ++k) {
          if (levels[k] >= wanted) {
            threshold = std::ldexp(excess, -k);
            break;
          }
        }
      }
      ex_.forEach(n_, [=] GALSCULPT_LAMBDA(int v) {
        const bool turned = changed[v];
        changed[v] = 0;
        if (!turned && !(rise[v] > threshold)) return;
        double slope = 0.0;  // along this vertex's shortened step
        for (int k = 0; k < 3; ++k) slope += length[v] * g[3 * v + k] * delta[3 * v + k];
        const double curvature = rise[v] - slope;
        // Never to nothing: a vertex held still every iteration would never get there (the
        // body's backtracking once froze the human figure the same way).
        double factor = 0.5;
        if (slope < 0.0 && curvature > 0.0)
          factor = fmax(0.1, fmin(0.5, -slope / (2.0 * curvature)));
        else if (!(slope < 0.0))
          factor = 0.1;  // no descent here
        length[v] *= factor;
        changed[v] = 1;
      });
      ex_.sum(
          n_, [=] GALSCULPT_LAMBDA(int v) { return static_cast<double>(changed[v]); }, sc + kCount);
      ex_.forEach(tets_, [=] GALSCULPT_LAMBDA(int t) {
        dirty[t] = changed[tv[4 * t]] | changed[tv[4 * t + 1]] | changed[tv[4 * t + 2]] |
                   changed[tv[4 * t + 3]];
      });
      ex_.forEach(3 * n_,
                  [=] GALSCULPT_LAMBDA(int i) { trial[i] = x[i] + length[i / 3] * delta[i]; });
      ex_.sum(
          tets_, [=] GALSCULPT_LAMBDA(int t) { return static_cast<double>(dirty[t]); },
          sc + kGuardElements);
      evaluateTrialPositions(dirty);
      ex_.sum(
          3 * n_, [=] GALSCULPT_LAMBDA(int i) { return length[i / 3] * g[i] * delta[i]; },
          sc + kGuardSlope);
      ex_.read(scalars_.data(), read, kScalars);
      ++result.backtracks;
      result.energyPasses += read[kGuardElements] / std::max(tets_, 1);
      if (!(read[kCount] > 0.0) || !std::isfinite(read[kE1])) return false;
      if (read[kE1] <= read[kE0] + sufficient * read[kGuardSlope] + 1e-12 * std::abs(read[kE0]) &&
          read[kTrialInverted] <= read[kInverted])
        return true;
    }
    return false;
  }

  // The guarded step (each vertex's length times its Newton step) becomes the step: delta_ and
  // its slope (kSlope); the trial already evaluated is its full length.
  void foldGuardIntoStep() {
    double* delta = delta_.data();
    const double* length = guardLength_.data();
    double* sc = scalars_.data();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) { delta[i] *= length[i / 3]; });
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc[kSlope] = sc[kGuardSlope]; });
  }

  // The next trial length after `length` failed: the minimum of the quadratic through e0, the
  // slope and e1, kept within a tenth and a half of `length` (a step 2^-17 too long then takes
  // about five evaluations, not seventeen halvings); half where the energy says nothing (an
  // inversion, no descent direction).
  static double shorterStep(double length, double e0, double e1, const double* read) {
    const double slope = read[kSlope];
    const double curvature = e1 - e0 - slope * length;  // of the quadratic, times length^2
    if (!std::isfinite(e1) || read[kTrialInverted] > read[kInverted] || !(slope < 0.0) ||
        !(curvature > 0.0))
      return 0.5 * length;
    return std::clamp(-slope * length * length / (2.0 * curvature), 0.1 * length, 0.5 * length);
  }

  // The sub-step's end, one captured section and one read: the residual at the accepted
  // positions (relative to the body's 1 g weight), contact forces, finiteness, velocities.
  void endSubstep(double h, SubstepOutcome& result) {
    ex_.captured(1, graphKey(h, -1), [&] { finishSubstep(h); });
    double read[kScalars];
    ex_.read(scalars_.data(), read, kScalars);
    result.residual = relativeResidual(read);
    const double pieceResidual = pieceResidual_.measure(
        ex_, pieces(), g_.data(), tmp_.data(), fixed_.data(), mass_.data(), model_.gravity.norm());
    result.pieceResidual = pieceResidual < 0.0 ? result.residual : pieceResidual;
    result.invertedElements = static_cast<int>(read[kTrialInverted]);  // the accepted trial's
    contact_.readForces(result.contactForces, contactMoments_);
    // Otherwise the caller restores x and v.
    if (read[kBad] > 0.0 || !std::isfinite(result.energy)) result.ok = false;
  }

  void finishSubstep(double h) {
    double* sc = scalars_.data();
    const double* x = x_.data();
    const double* xn = xn_.data();
    double* v = v_.data();
    acceptedResidual();
    ex_.sum(
        3 * n_,
        [=] GALSCULPT_LAMBDA(int i) { return x[i] == x[i] && fabs(x[i]) <= 1.7e308 ? 0.0 : 1.0; },
        sc + kBad);
    contact_.sumForces(x, fixed_.data(), mass_.data(), h_step_);
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) { v[i] = (x[i] - xn[i]) / h; });
  }

  // The Newton step's measures: e0 (kE0), the slope g.delta (kSlope), |delta|_inf
  // (kDeltaMax), and whether g or delta holds a NaN or infinity (kBad).
  void stepMeasures() {
    double* sc = scalars_.data();
    const double* x = x_.data();
    objective(x, kElastic, kContact, dampedK_.data(), kE0);
    const double* g = g_.data();
    const double* delta = delta_.data();
    ex_.sum(
        3 * n_, [=] GALSCULPT_LAMBDA(int i) { return g[i] * delta[i]; }, sc + kSlope);
    ex_.sum(
        3 * n_,
        [=] GALSCULPT_LAMBDA(int i) {
          return g[i] == g[i] && fabs(g[i]) <= 1.7e308 && delta[i] == delta[i] &&
                         fabs(delta[i]) <= 1.7e308
                     ? 0.0
                     : 1.0;
        },
        sc + kBad);
    ex_.maximum(
        3 * n_, [=] GALSCULPT_LAMBDA(int i) { return fabs(delta[i]); }, sc + kDeltaMax);
    // What the vertex guard compares its trials with (the contact term holds x's energies here).
    if (settings_->vertexGuard)
      vertexPotential(x, elemEnergy_.data(), dampedK_.data(), potentialAtX_.data());
  }

  // Elastic and contact energies and the potential at x + length delta (slots kTrialElastic,
  // kTrialContact, kE1), with the trial's gradient.
  void evaluateTrial(double length) {
    double* trial = trial_.data();
    const double* x = x_.data();
    const double* delta = delta_.data();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) { trial[i] = x[i] + length * delta[i]; });
    evaluateTrialPositions(nullptr);
  }

  // The same at the positions in trial_; with `only`, just the flagged elements evaluated again
  // (the others unchanged since the last trial: the vertex guard's rounds).
  void evaluateTrialPositions(const std::uint8_t* only) {
    const double* trial = trial_.data();
    elementPass(trial, false, trialGrad_.data(), kTrialElastic, kTrialInverted, only);
    dampedProduct(trial, tmp_.data());
    contact(trial, nullptr, kTrialContact);
    objective(trial, kTrialElastic, kTrialContact, tmp_.data(), kE1);
  }

  // Everything a captured Newton step bakes in: a replay is valid only for the same key.
  std::uint64_t graphKey(double h, int iteration) const {
    const StepSettings& s = *settings_;
    const MultigridSettings& m = s.multigridSettings;
    std::uint64_t key = 1469598103934665603ull;
    auto mix = [&](std::uint64_t v) { key = (key ^ v) * 1099511628211ull; };
    auto mixDouble = [&](double d) {
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      mix(bits);
    };
    mixDouble(h);
    mix(static_cast<std::uint64_t>(iteration));
    mix(static_cast<std::uint64_t>(s.newtonIterations));
    mix(mgRevision_);
    mix(anchorCount_);
    mix(static_cast<std::uint64_t>(contact_.colliders()));
    mix(reinterpret_cast<std::uintptr_t>(anchorVertices_.data()));
    mix(reinterpret_cast<std::uintptr_t>(anchorTargets_.data()));
    mix(reinterpret_cast<std::uintptr_t>(contact_.poses()));
    mix(reinterpret_cast<std::uintptr_t>(plastic_.inverse()));
    mix(plastic_.active());
    mix(static_cast<std::uint64_t>(m.preSweeps) << 32 | static_cast<std::uint32_t>(m.postSweeps));
    mix(static_cast<std::uint64_t>(m.coarseIterations) << 32 |
        static_cast<std::uint32_t>(m.cycles));
    mix(m.jacobi);
    mix(m.jacobiOnDevice);
    mixDouble(m.jacobiWeight);
    mixDouble(s.stiffnessTolerance);
    mix(s.reuseStiffness);  // the trial counts switched cracks only for chord steps
    return key;
  }

  // delta = A^-1 (-g) by the multigrid: V-cycles (the residual norms go to slots kR0, kR1; no
  // host read) or PCG (host reads; its reduction in pcgReduction_).
  // The reference's linear solve: CHOLMOD on the system in host memory. A system that is not
  // positive definite leaves a NaN step, which fails the sub-step (retried with half the step).
  void solveDirect() {
    double* delta = delta_.data();
    double* b = rhs();
    const double* g = g_.data();
    double* sc = scalars_.data();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) {
      b[i] = -g[i];
      delta[i] = 0.0;
    });
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc[kR0] = sc[kR1] = 0.0; });
    if constexpr (Exec::kHostMemory) {
      if (!direct_) direct_ = std::make_unique<DirectSolver>(model_.pattern);
      if (!direct_->solve(h_.data(), b, delta)) delta[0] = std::numeric_limits<double>::quiet_NaN();
    } else {
      throw std::logic_error(cudaUnsupportedReason(model_, *settings_));
    }
  }

  void solveLinear() {
    const StepSettings& s = *settings_;
    const MultigridSettings& ms = s.multigridSettings;
    typename MultigridCycle<Exec>::Settings mgs;
    mgs.preSweeps = ms.preSweeps;
    mgs.postSweeps = ms.postSweeps;
    mgs.jacobi = ms.jacobi || (!Exec::kHostMemory && ms.jacobiOnDevice && ms.pcg);
    mgs.jacobiWeight = ms.jacobiWeight;
    mgs.coarseCholesky = ms.coarseCholesky;
    mgs.coarseIterations = ms.coarseIterations;
    mgs.cycles = ms.cycles;
    double* delta = delta_.data();
    double* b = rhs();
    const double* g = g_.data();
    const std::uint8_t* fixed = fixed_.data();
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) {
      b[i] = -g[i];
      delta[i] = 0.0;
    });
    const double* a = h_.data();
    double* sc = scalars_.data();
    double* ap = pcgAp_.data();
    if (!ms.pcg) {  // (PCG sums |b|^2 itself; kR0 and kR1 are read only for the V-cycles)
      ex_.sum(
          3 * n_, [=] GALSCULPT_LAMBDA(int i) { return b[i] * b[i]; }, sc + kR0);
      mg_.cycles(a, b, delta, mgs);
      mg_.multiplyFine(a, delta, ap);
      ex_.sum(
          3 * n_, [=] GALSCULPT_LAMBDA(int i) { return (b[i] - ap[i]) * (b[i] - ap[i]); },
          sc + kR1);
    } else {
      const auto r = mg_.pcg(a, b, delta, mgs, ms.pcgTolerance, ms.pcgMaxIterations, pcgTarget());
      pcgReduction_ = r.reduction;
      pcgIterations_ += r.iterations;
    }
    ex_.forEach(3 * n_, [=] GALSCULPT_LAMBDA(int i) {
      if (fixed[i / 3]) delta[i] = 0.0;
    });
  }

  // PCG's absolute target: never further than half the residual the sub-step must reach (an
  // inexact Newton step), less while a piece is above its own (piecesWithinTolerance).
  double pcgTarget() const {
    return std::min(0.5 * settings_->residualTolerance * std::max(weight(), forceScale_),
                    pieceTargetCap_);
  }

  // ---- plasticity and fracture --------------------------------------------------------------

  int plasticUpdate() {
    gradientAtX_ = false;  // rest shapes flow
    return plastic_.returnMap(x_.data(), damaged_.data(), tetVertices_.data(), tetEdges_.data(),
                              rest_.data(), elemEnergy_.data());
  }

  // Each edge's stress as the fracture pass sees it at `state` (element maximum, then the
  // kernel mean when the field has one), 0 on damaged edges: for tests and views. The kernel
  // mean is taken on every edge, not only near hot ones; no damage changes.
  // Needs the model's fracture field.
  std::vector<double> edgeStress(const SimState& state, const StepSettings& settings) {
    syncIn(state, settings);
    fracture_->evaluate(elementInputs(), x_.data(), damaged_.data(), true);
    std::vector<double> ratio(edges_), out(edges_, 0.0);
    if (edges_ > 0) ex_.download(fracture_->stressRatio(), ratio.data(), ratio.size());
    for (int e = 0; e < edges_; ++e)
      if (!hostDamaged_[e]) out[e] = ratio[e] * model_.fracture.threshold[e];
    return out;
  }

  FractureReport fracturePass() {
    FractureReport report = fracture_->findBreaks(elementInputs(), x_.data(), damaged_.data());
    if (report.newlyDamaged > 0) {
      fracture_->markBroken(damaged_.data());
      damaged_.download(hostDamaged_.data(), hostDamaged_.size());
      const std::vector<int> parted =
          crackedSectionEdges(model_, model_.fracture.tetNeighbours, hostDamaged_,
                              model_.fracture.settings.partingFraction);
      if (!parted.empty()) {
        for (const int e : parted) hostDamaged_[e] = 1;
        damaged_.upload(hostDamaged_);
        report.newlyDamaged += static_cast<int>(parted.size());
      }
      ++damageRevision_;
      ++hostDamageChanges_;
      gradientAtX_ = false;
    }
    return report;
  }

  // ---- setup ----------------------------------------------------------------------------

  void ensureMultigrid(const StepSettings& s) {
    if (multigrid_ && gridHandles_ == s.gridHandles) return;
    multigrid_ = std::make_unique<Multigrid>(model_.pattern, model_.mesh.vertices, model_.edges,
                                             s.gridHandles);
    gridHandles_ = s.gridHandles;
    if (s.multigridSettings.splitAggregates)
      multigrid_->updateDamage(model_.edges, hostDamaged_, damageRevision_);
    mg_.upload(buildMultigridLayout(*multigrid_, model_.pattern));
    ++mgRevision_;
  }

  // The debris rule (solver/fracture/debris.h): the vertices of pieces under
  // model_.debrisRemoval of the body's rest volume are held where they are, out of the solve,
  // and the elements around them stop pushing back on the rest of the body.
  void updateRemovedDebris() {
    std::vector<std::uint8_t> removed = debrisVertices(census(), model_.debrisRemoval);
    if (removed.empty()) removed.assign(n_, 0);
    if (removed == hostRemoved_) return;
    hostRemoved_ = std::move(removed);
    removed_.upload(hostRemoved_);
    removedVertices_.clear();
    for (int v = 0; v < n_; ++v)
      if (hostRemoved_[v]) removedVertices_.push_back(v);
  }

  // Anchored vertices and their targets at `time`, and the colliders' poses (host-computed,
  // uploaded when they change); a rigid pendulum where its angular velocity takes it in the
  // sub-step h (advancePendulum).
  void prepareAnchorsAndColliders(double time, double h) {
    std::vector<std::uint8_t> fixed(n_, 0);
    std::vector<int> vertices;
    std::vector<double> targets;
    for (const AnchorConstraint& a : *anchors_) {
      const Vec3 offset = anchorOffset(a, time);
      for (size_t i = 0; i < a.vertices.size(); ++i) {
        const int v = a.vertices[i];
        fixed[v] = 1;
        const Vec3 p = (a.origin.empty() ? model_.mesh.vertices[v] : a.origin[i]) + offset;
        vertices.push_back(v);
        targets.insert(targets.end(), {p.x(), p.y(), p.z()});
      }
    }
    for (size_t i = 0; i < removedVertices_.size(); ++i) {
      const int v = removedVertices_[i];
      if (fixed[v]) continue;  // an anchor keeps it on its path
      fixed[v] = 1;
      vertices.push_back(v);
      targets.insert(targets.end(), removedTargets_.begin() + 3 * i,
                     removedTargets_.begin() + 3 * i + 3);
    }
    if (fixed != hostFixed_) {
      hostFixed_ = fixed;
      fixed_.upload(hostFixed_);
    }
    anchorCount_ = vertices.size();
    if (vertices != hostAnchorVertices_) {
      hostAnchorVertices_ = vertices;
      anchorVertices_.upload(vertices);
    }
    if (targets != hostAnchorTargets_) {
      hostAnchorTargets_ = targets;
      anchorTargets_.upload(targets);
    }
    contact_.place(colliderStates_, time, h);
  }

  double* rhs() { return pcgB_.data(); }
  const double* frozenBlocks() const { return frozenIsK_ ? k_.data() : frozen_.data(); }

  // The scalars kernels hand back to the host, slots of one executor array (read together).
  enum Slot {
    kElastic,
    kContact,
    kTrialElastic,
    kTrialContact,
    kE0,
    kE1,
    kSlope,
    kBad,
    kDeltaMax,
    kResidual,
    kR0,
    kR1,
    kPap,
    kCount,
    kInverted,
    kTrialInverted,
    kGuardSlope,
    kGuardElements,
    kKept,
    kSwitched,
    kGuardLevel,
    kForceScale = kGuardLevel + kGuardLevels + 1,
    kScalars
  };

 private:
  Exec& ex_;
  const SimModel& model_;
  MultigridCycle<Exec> mg_;
  ContactTerm<Exec> contact_;
  PlasticState<Exec> plastic_;
  std::unique_ptr<Multigrid> multigrid_;
  std::unique_ptr<DirectSolver> direct_;  // the reference's (host memory only)
  std::vector<int> gridHandles_;
  const StepSettings* settings_ = nullptr;
  const std::vector<AnchorConstraint>* anchors_ = nullptr;  // the stepped state's
  int n_ = 0, tets_ = 0, edges_ = 0, blocks_ = 0;
  double time_ = 0.0, h_step_ = 0.0, modelSize_ = 1.0, massNorm_ = 0.0, pcgReduction_ = 0.0;
  int pcgIterations_ = 0;        // the current sub-step's
  double forceScale_ = 0.0;      // the last residual's scale (N): the next solves' target
  double switchedCracks_ = 0.0;  // elements whose open cracks the last accepted step changed
  Clock::time_point frameStart_ = Clock::now();
  std::uint64_t mgRevision_ = 0;  // bumped whenever the hierarchy is uploaded again
  bool frozenIsK_ = true;
  bool predicted_ = false;      // this sub-step's Newton started from x_n + h v_n, not yet checked
  bool systemSkipped_ = false;  // the last iteration's null step built no system (takeNullStep)
  template <typename T>
  using Mirror = typename Exec::template Mirror<T>;
  Mirror<int> tetVertices_, tetEdges_, rowStart_, columns_, diagonal_;
  Mirror<int> vertexSlotStart_, vertexSlots_, blockSlotStart_, blockSlots_;
  Mirror<kernels::RestData> rest_;
  Mirror<double> mass_;
  Buffer<int> blockRow_;
  Buffer<int> transposedBlock_;  // (blocks) the index of block (c, r) for block (r, c)
  Buffer<double> x_, v_, xn_, vn_, xhat_, grad_, trialGrad_, acceptedGrad_, g_, delta_, trial_,
      dampedK_, tmp_, savedX_, savedV_;
  Buffer<double> elemEnergy_, elemInverted_, elemGrad_, elemHess_, k_, frozen_, h_, scalars_;
  // The trial's element energies and inversions (elemEnergy_, elemInverted_: at x), and the
  // vertex guard's per-vertex step lengths and potentials at x and at the trial.
  Buffer<double> trialEnergy_, trialInverted_, guardLength_, potentialAtX_, potentialAtTrial_;
  Buffer<std::uint8_t> guardChanged_, guardDirty_;
  // Kept element stiffnesses (StepSettings::stiffnessTolerance): the deformation gradient each
  // element's stiffness in elemHess_ was evaluated at in this sub-step (NaN: evaluate again)
  // and whether this pass evaluated it. Damage needs no check: a damaged element is evaluated
  // every time, and an intact one's stiffness does not depend on its neighbours'.
  Buffer<double> stiffnessF_;
  Buffer<std::uint8_t> stiffnessFresh_;
  // Each element's open cracks where the stiffness was evaluated and at the last trial: a chord
  // step is taken only while few differ (substep).
  Buffer<std::uint8_t> stiffnessOpened_, trialOpened_;
  Buffer<double> pcgB_, pcgAp_;  // the linear system's right-hand side and A delta
  Buffer<std::uint8_t> fixed_, damaged_;
  Buffer<int> anchorVertices_;
  Buffer<double> anchorTargets_;
  size_t anchorCount_ = 0;
  std::vector<ColliderState> colliderStates_;     // the stepped state's, advanced per sub-step
  std::vector<double> contactMoments_;            // (nColliders) the last sub-step's, N m
  std::unique_ptr<FracturePass<Exec>> fracture_;  // with the model's fracture field
  // Host shadows: what the device holds, to upload only changes.
  std::vector<double> hostX_, hostV_, hostAnchorTargets_;
  std::vector<std::uint8_t> hostDamaged_, hostFixed_, hostRemoved_;
  AcceleratedStart<Exec> accelerated_;  // the pieces' starts (startPiecesAccelerated)
  PieceResidual<Exec> pieceResidual_;   // the residual piece by piece (piecesWithinTolerance)
  // PCG's absolute target at most this in this sub-step (piecesWithinTolerance).
  double pieceTargetCap_ = std::numeric_limits<double>::infinity();
  // Counts the changes of hostDamaged_'s content (syncIn, the fracture pass), what the host's
  // structures derived from the damage are keyed on. (damageRevision_ cannot be: a backend may be
  // handed several states under one revision, and syncIn compares their damage by content.)
  std::uint64_t hostDamageChanges_ = 0;
  PieceCensus census_;  // census(): for the damage change censusFor_
  std::uint64_t censusFor_ = ~std::uint64_t{0};
  PieceLayout pieces_;  // pieces(): for the damage change piecesFor_
  std::uint64_t piecesFor_ = ~std::uint64_t{0};
  // Whether elemGrad_ holds every element's gradient at x_ under the current damage, rest shapes
  // and removed debris: true from a Newton iteration's accept until x_ or any of those changes
  // (what the pieces' start reads at x_n instead of evaluating them again).
  bool gradientAtX_ = false;
  Buffer<std::uint8_t> removed_;        // (nVerts) 1 on removed debris
  std::vector<int> removedVertices_;    // ascending
  std::uint64_t removedFor_ = 0;        // the damage change removedVertices_ is for (0: none yet)
  std::vector<double> removedTargets_;  // (3 per removed vertex) where each is held
  std::vector<int> hostAnchorVertices_;
  std::uint64_t damageRevision_ = ~std::uint64_t{0};
};

// The device solver on its own executor, behind the solver's StepBackend interface ("cuda" on the
// GPU; "host" in the tests). A device error mid-frame throws before the state is written back,
// so the caller may run the frame again elsewhere.
template <typename Exec>
class ExecutorStepBackend final : public StepBackend {
 public:
  explicit ExecutorStepBackend(const SimModel& model) : solver_(executor_, model) {}
  std::string name() const override { return Exec::kName; }
  bool offloads() const override { return !Exec::kHostMemory; }
  StepReport step(SimState& state, const StepSettings& settings) override {
    return solver_.step(state, settings);
  }

 private:
  Exec executor_;
  FrameSolver<Exec> solver_;
};

}  // namespace galsculpt
