// The incremental potential of backward Euler and its derivatives, on the executor: the
// coordinate terms (coordinate_terms.h: inertia, gravity, Rayleigh damping, the soft anchors'
// springs, summed per coordinate in one launch), the elastic term (the element pass and its
// gathers into the gradient and the stiffness blocks) and the contact term (contact_term.h);
// the backward-Euler gradient g and the Newton system H; the potential at a trial step, whole
// or vertex by vertex (the vertex guard). Its functions launch and reduce into the frame's
// scalars (frame_scalars.h), never read: the frame decides when to synchronize.
//
//   E(y) = sum_i m_i/(2h^2) |y_i - xhat_i|^2 - m_i g.y_i + 1/(2h) (alpha m_i |y_i - x_n,i|^2
//          + (y - x_n).beta K0 (y - x_n)) + k_i/2 |y_i - t_i|^2 + elastic(y) + contact(y)
// (k_i, t_i: the soft anchors' springs, held_vertices.h; zero on most vertices)
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>

#include "solver/fem/dense_kernels.h"
#include "solver/fem/element_lanes.h"
#include "solver/frame/contact_term.h"
#include "solver/frame/coordinate_terms.h"
#include "solver/frame/element_pass.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/plastic_state.h"
#include "solver/frame/stiffness_gather.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class IncrementalPotential {
 public:
  IncrementalPotential(Exec& ex, const SimModel& model, FrameData<Exec>& data,
                       ContactTerm<Exec>& contact, const PlasticState<Exec>& plastic)
      : ex_(ex), model_(model), d_(data), contact_(contact), plastic_(plastic) {}

  // Energies, forces and (withHessian) stiffnesses of every element at positions y, gathered
  // into `gradient` (3n) and, with the Hessian, into the stiffness blocks. The total energy goes
  // to *energyOut, the number of intact elements turned inside out (det F <= 0) to *invertedOut:
  // the line search refuses a step that turns more of them than there were.
  // At a trial (not withHessian) the per-element energies and inversions go to trialEnergy and
  // trialInverted, otherwise to elemEnergy and elemInverted. With `only`, just the elements
  // flagged there are evaluated (the vertex guard's rounds); the others keep their last values.
  // In a local iteration (local_region.h) only the region's elements are evaluated, and only
  // their corners' sums gathered again: `gradient` must hold the others' already (the stiffness
  // blocks always do: a block is gathered again whenever one of its elements was evaluated).
  void elementPass(const double* y, bool withHessian, double* gradient, double* energyOut,
                   double* invertedOut, const std::uint8_t* only = nullptr) {
    const std::uint8_t* touched = nullptr;
    if (!only) {
      only = d_.evaluated();
      touched = d_.touched();
    }
    const ElementInputs in = elementInputs();
    double* energy = withHessian ? d_.elemEnergy.data() : d_.trialEnergy.data();
    double* inverted = withHessian ? d_.elemInverted.data() : d_.trialInverted.data();
    double* eg = d_.elemGrad.data();
    double* eh = d_.elemHess.data();
    const MaterialModel model = model_.material.model;
    const Lame lame = model_.material.elementLame();
    const bool resists = model_.material.compressionResists;
    const kernels::Hessian mode =
        withHessian ? kernels::Hessian::ProjectedSpd : kernels::Hessian::None;
    // Kept stiffnesses: an element whose deformation gradient moved less than the tolerance
    // (every entry) since its stiffness was evaluated keeps it (its energy and force are new).
    // (beginSubstep marks every record stale: nothing is kept across sub-steps.)
    const double keep = withHessian ? d_.settings->stiffnessTolerance : 0.0;
    const std::uint8_t* fresh = d_.stiffnessFresh.data();
    if (keep > 0.0 && only) {  // what this pass does not evaluate it keeps
      std::uint8_t* clear = d_.stiffnessFresh.data();
      ex_.forEach(d_.tets, [=] GALSCULPT_LAMBDA(int t) { clear[t] = 0; });
    }
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
                           d_.stiffnessF.data(),
                           d_.stiffnessFresh.data(),
                           withHessian ? d_.stiffnessOpened.data() : d_.trialOpened.data(),
                           only};
    kernels::LaneKernel lanes = nullptr;
    kernels::CrackedLaneKernel crackedLanes = nullptr;
    if constexpr (Exec::kHostMemory) {
      const kernels::LaneBuild build = kernels::chosenLaneBuild();
      lanes = kernels::laneKernel(build);
      // (Without stiffness the damaged elements' lanes were no faster than the scalar kernel:
      // what they take over is mostly the stiffness.)
      if (withHessian) crackedLanes = kernels::crackedLaneKernel(build);
    }
    launchElementPass(ex_, pass, d_.tets, lanes, crackedLanes);
    if (keep > 0.0)
      ex_.sum(
          d_.tets,
          [=] GALSCULPT_LAMBDA(int t) { return fresh[t] || (only && !only[t]) ? 0.0 : 1.0; },
          &d_.sc()->kept);
    ex_.sum(
        d_.tets, [=] GALSCULPT_LAMBDA(int t) { return energy[t]; }, energyOut);
    ex_.sum(
        d_.tets, [=] GALSCULPT_LAMBDA(int t) { return inverted[t]; }, invertedOut);
    if (!withHessian && d_.settings->reuseStiffness) {
      // The damaged elements whose open cracks differ from where the stiffness was evaluated.
      const std::uint8_t* atStiffness = d_.stiffnessOpened.data();
      const std::uint8_t* atTrial = d_.trialOpened.data();
      ex_.sum(
          d_.tets, [=] GALSCULPT_LAMBDA(int t) { return atStiffness[t] != atTrial[t] ? 1.0 : 0.0; },
          &d_.sc()->switched);
    }
    const int* vStart = d_.vertexSlotStart.data();
    const int* vSlots = d_.vertexSlots.data();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
      if (touched && !touched[v]) return;
      double acc[3] = {0.0, 0.0, 0.0};
      for (int i = vStart[v]; i < vStart[v + 1]; ++i) {
        const int slot = vSlots[i], t = slot / 4, a = slot % 4;
        for (int k = 0; k < 3; ++k) acc[k] += eg[12 * t + 3 * a + k];
      }
      for (int k = 0; k < 3; ++k) gradient[3 * v + k] = acc[k];
    });
    if (!withHessian) return;
    double* kb = d_.stiffness.data();
    // Only the blocks of an element whose stiffness this pass evaluated change (null: all).
    const std::uint8_t* freshOnly = keep > 0.0 ? fresh : only;
    const int* blockRow = d_.blockRow.data();
    const int* columns = d_.columns.data();
    const int* transposed = d_.transposedBlock.data();
    const std::uint8_t* opened = d_.stiffnessOpened.data();
    // The blocks on and above the diagonal from the elements' packed upper blocks, then those
    // below as their partners' transposes: an element's stiffness is read once, not its six
    // lower blocks again (the gather reads scattered elements: a sixth of a 100-cut frame).
    // (An element's blocks join two of its corners: none without both touched changes.)
    // In host memory by ranges of rows, element by element (stiffness_gather.h: the same bits).
    if constexpr (Exec::kHostMemory) {
      if (!hostGather_)
        hostGather_ = std::make_unique<StiffnessGather>(model_.pattern, model_.scatter,
                                                        model_.tetVertexArray());
      hostGather_->gatherUpper(eh, opened, freshOnly, touched, kb);
    } else {
      gatherUpperByBlocks(eh, opened, freshOnly, touched, kb);
    }
    ex_.forEach(d_.blocks, [=] GALSCULPT_LAMBDA(int b) {
      if (blockRow[b] <= columns[b]) return;
      if (touched && !(touched[blockRow[b]] && touched[columns[b]])) return;
      const double* upper = kb + 9 * static_cast<size_t>(transposed[b]);
      for (int j = 0; j < 3; ++j)
        for (int r = 0; r < 3; ++r) kb[9 * b + r + 3 * j] = upper[j + 3 * r];
    });
  }

  // The upper blocks' gather a thread per block (a device's; stiffness_gather.h has the host's).
  // Public only because nvcc refuses extended lambdas in private member functions.
  void gatherUpperByBlocks(const double* eh, const std::uint8_t* opened,
                           const std::uint8_t* freshOnly, const std::uint8_t* touched, double* kb) {
    const int* bStart = d_.blockSlotStart.data();
    const int* bSlots = d_.blockSlots.data();
    const int* blockRow = d_.blockRow.data();
    const int* columns = d_.columns.data();
    ex_.forEach(d_.blocks, [=] GALSCULPT_LAMBDA(int b) {
      if (blockRow[b] > columns[b]) return;
      if (touched && !(touched[blockRow[b]] && touched[columns[b]])) return;
      if (freshOnly) {  // a block of kept (or not evaluated) stiffnesses only is what it was
        bool any = false;
        for (int i = bStart[b]; i < bStart[b + 1] && !any; ++i) any = freshOnly[bSlots[i] / 16];
        if (!any) return;
      }
      double acc[9] = {};
      for (int i = bStart[b]; i < bStart[b + 1]; ++i) {
        const int slot = bSlots[i], t = slot / 16, a = (slot % 16) / 4, c = slot % 4;
        // Zero and not written (adding its zeros would leave the sums' bits as they are).
        if (ElementPass::zeroStiffness(opened[t])) continue;
        const double* h = eh + ElementPass::kPackedHessian * static_cast<size_t>(t);
        if (a <= c) {
          const double* blk = h + 9 * ElementPass::packedBlock(a, c);
          for (int k = 0; k < 9; ++k) acc[k] += blk[k];
        } else {  // the mirror of block (c, a)
          const double* blk = h + 9 * ElementPass::packedBlock(c, a);
          for (int j = 0; j < 3; ++j)
            for (int r = 0; r < 3; ++r) acc[r + 3 * j] += blk[j + 3 * r];
        }
      }
      for (int i = 0; i < 9; ++i) kb[9 * b + i] = acc[i];
    });
  }

  ElementInputs elementInputs() const {
    return {d_.tetVertices.data(), d_.tetEdges.data(), d_.damaged.data(), d_.rest.data(),
            plastic_.shapes(),     plastic_.shaped(),  d_.removed.data(), plastic_.strain()};
  }

  // out = beta K0 (y - x_n).
  void dampedProduct(const double* y, double* out) {
    const double* xn = d_.xn.data();
    const double* frozen = d_.frozenBlocks();
    const int* rowStart = d_.rowStart.data();
    const int* columns = d_.columns.data();
    const double beta = model_.material.dampingStiffness;
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int r) {
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

  // Penalty contact at y: energy into *energyOut; gradient added (when given).
  void contact(const double* y, double* gradient, double* energyOut) {
    contact_.energy(y, d_.fixed.data(), d_.mass.data(), d_.h, gradient, energyOut);
  }

  // What the coordinate terms (coordinate_terms.h) read, with βK₀(y - x_n) for the y at hand.
  CoordinateInputs coordinateInputs(const double* dampedK) const {
    return {d_.xhat.data(),
            d_.xn.data(),
            d_.mass.data(),
            d_.springK.data(),
            d_.springTarget.data(),
            dampedK,
            d_.h,
            model_.material.dampingMass,
            {model_.gravity.x(), model_.gravity.y(), model_.gravity.z()}};
  }

  // The incremental potential at y into *out (the elastic and contact energies at y already
  // summed, in *elastic and *contactEnergy).
  void objective(const double* y, const double* elastic, const double* contactEnergy,
                 const double* dampedK, double* out) {
    const CoordinateInputs c = coordinateInputs(dampedK);
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return CoordinateTerms::energy(c, i, y); }, out);
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { *out += *elastic + *contactEnergy; });
  }

  // Each vertex's share of the incremental potential at y: a quarter of each element energy
  // around it, its own inertia, gravity, damping and contact terms (they sum to the potential).
  // `energy`: the elements' energies at y; the contact term's must be y's.
  void vertexPotential(const double* y, const double* energy, const double* dampedK, double* out) {
    const CoordinateInputs c = coordinateInputs(dampedK);
    const int* vStart = d_.vertexSlotStart.data();
    const int* vSlots = d_.vertexSlots.data();
    const double* contactEnergy = contact_.perVertex();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
      double sum = contactEnergy ? contactEnergy[v] : 0.0;
      for (int i = vStart[v]; i < vStart[v + 1]; ++i) sum += 0.25 * energy[vSlots[i] / 4];
      for (int k = 0; k < 3; ++k) sum += CoordinateTerms::energy(c, 3 * v + k, y);
      out[v] = sum;
    });
  }

  // g: the coordinate terms' gradients with the pass terms' (elastic and contact, in `grad`),
  // zero on anchored vertices.
  void backwardEulerGradient(const double* y, const double* grad, const double* dampedK,
                             double* g) {
    const CoordinateInputs c = coordinateInputs(dampedK);
    const std::uint8_t* fixed = d_.fixed.data();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) {
      g[i] = fixed[i / 3] ? 0.0 : CoordinateTerms::gradient(c, i, y, grad[i]);
    });
  }

  // H = K + beta/h K0 + contact + M (1/h^2 + alpha/h) + the springs' k I, anchored rows and
  // columns identity-scaled (and in a local iteration those outside the region).
  void buildSystem(const double* y) {
    const double* kb = d_.stiffness.data();
    const double* frozen = d_.frozenBlocks();
    double* hb = d_.system.data();
    const int* blockRow = d_.blockRow.data();
    const int* columns = d_.columns.data();
    const std::uint8_t* fixed = d_.solveFixed();
    // A local iteration's solve reads the region's rows only.
    const std::uint8_t* rows = d_.local ? d_.regionVertex.data() : nullptr;
    const double* mass = d_.mass.data();
    const double h = d_.h;
    const auto contactStiffness = contact_.stiffness(mass, h);
    const double betaOverH = model_.material.dampingStiffness / h;
    const CoordinateInputs coords = coordinateInputs(nullptr);
    ex_.forEach(d_.blocks, [=] GALSCULPT_LAMBDA(int b) {
      const int r = blockRow[b], c = columns[b];
      if (rows && !rows[r]) return;
      double out[9];
      for (int i = 0; i < 9; ++i) out[i] = kb[9 * b + i] + betaOverH * frozen[9 * b + i];
      if (r == c) {
        if (!fixed[r]) contactStiffness.add(r, y, out);
        const double m = mass[r] * CoordinateTerms::massCoefficient(coords);
        for (int i = 0; i < 3; ++i) out[4 * i] += m;
        const double own = CoordinateTerms::diagonal(coords, r);
        for (int i = 0; i < 3; ++i) out[4 * i] += own;
      }
      if (fixed[r] || fixed[c]) {
        const double diag = r == c ? mass[r] / (h * h) : 0.0;
        for (int i = 0; i < 9; ++i) out[i] = i % 4 == 0 ? diag : 0.0;
      }
      for (int i = 0; i < 9; ++i) hb[9 * b + i] = out[i];
    });
  }

  // The backward-Euler gradient at the accepted positions (g; the elastic and contact forces in
  // tmp) and its sums (residualSums).
  void acceptedResidual() {
    const double* x = d_.x.data();
    dampedProduct(x, d_.dampedK.data());
    ex_.copy(d_.tmp.data(), d_.acceptedGrad.data(), 3 * d_.n);
    contact(x, d_.tmp.data(), &d_.sc()->contact);
    backwardEulerGradient(x, d_.tmp.data(), d_.dampedK.data(), d_.g.data());
    residualSums();
  }

  // |g|^2 (residual) and the squared elastic and contact forces on the free vertices
  // (forceScale), from g and tmp.
  void residualSums() {
    const double* g = d_.g.data();
    const double* f = d_.tmp.data();
    const std::uint8_t* fixed = d_.fixed.data();
    FrameScalars* sc = d_.sc();
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return g[i] * g[i]; }, &sc->residual);
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return fixed[i / 3] ? 0.0 : f[i] * f[i]; },
        &sc->forceScale);
  }

  // The Newton step's measures: e0, the slope g.delta, |delta|_inf (deltaMax) and whether g or
  // delta holds a NaN or infinity (bad).
  void stepMeasures() {
    FrameScalars* sc = d_.sc();
    const double* x = d_.x.data();
    objective(x, &sc->elastic, &sc->contact, d_.dampedK.data(), &sc->e0);
    const double* g = d_.g.data();
    const double* delta = d_.delta.data();
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return g[i] * delta[i]; }, &sc->slope);
    ex_.sum(
        3 * d_.n,
        [=] GALSCULPT_LAMBDA(int i) {
          return g[i] == g[i] && fabs(g[i]) <= 1.7e308 && delta[i] == delta[i] &&
                         fabs(delta[i]) <= 1.7e308
                     ? 0.0
                     : 1.0;
        },
        &sc->bad);
    ex_.maximum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return fabs(delta[i]); }, &sc->deltaMax);
    // What the vertex guard compares its trials with (the contact term holds x's energies here).
    if (d_.settings->vertexGuard())
      vertexPotential(x, d_.elemEnergy.data(), d_.dampedK.data(), d_.potentialAtX.data());
  }

  // Elastic and contact energies and the potential at x + length delta (trialElastic,
  // trialContact, e1), with the trial's gradient.
  void evaluateTrial(double length) {
    double* trial = d_.trial.data();
    const double* x = d_.x.data();
    const double* delta = d_.delta.data();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { trial[i] = x[i] + length * delta[i]; });
    evaluateTrialPositions(nullptr);
  }

  // The same at the positions in trial; with `only`, just the flagged elements evaluated again
  // (the others unchanged since the last trial: the vertex guard's rounds).
  void evaluateTrialPositions(const std::uint8_t* only) {
    const double* trial = d_.trial.data();
    FrameScalars* sc = d_.sc();
    elementPass(trial, false, d_.trialGrad.data(), &sc->trialElastic, &sc->trialInverted, only);
    dampedProduct(trial, d_.tmp.data());
    contact(trial, nullptr, &sc->trialContact);
    objective(trial, &sc->trialElastic, &sc->trialContact, d_.tmp.data(), &sc->e1);
  }

 private:
  Exec& ex_;
  const SimModel& model_;
  FrameData<Exec>& d_;
  ContactTerm<Exec>& contact_;
  const PlasticState<Exec>& plastic_;
  std::unique_ptr<StiffnessGather> hostGather_;  // host memory only
};

}  // namespace galsculpt
