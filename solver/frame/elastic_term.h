// The elastic term of the incremental potential (incremental_potential.h): every element's
// energy, force and (with the Hessian) projected stiffness at positions y by the element pass
// (element_pass.h; the SIMD lanes in host memory, one thread an element on a device), the
// forces gathered per vertex into the gradient and the stiffnesses per block into the Newton
// system's base (stiffness_gather.h in host memory, a thread per block on a device). The
// element kernels and materials are the one source of solver/fem/. Its launches reduce into
// the frame's scalars and never read them.
#pragma once

#include <cstdint>
#include <memory>

#include "solver/fem/dense_kernels.h"
#include "solver/fem/element_lanes.h"
#include "solver/frame/element_pass.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/pass_terms.h"
#include "solver/frame/plastic_state.h"
#include "solver/frame/stiffness_gather.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class ElasticTerm {
 public:
  ElasticTerm(Exec& ex, const SimModel& model, FrameData<Exec>& data,
              const PlasticState<Exec>& plastic)
      : ex_(ex), model_(model), d_(data), plastic_(plastic) {}
  explicit ElasticTerm(const PassTermContext<Exec>& c)
      : ElasticTerm(c.ex, c.model, c.data, c.plastic) {}

  // ---- as a pass term (pass_terms.h) ------------------------------------------------------

  static double* energySlot(FrameScalars* sc, bool trial) {
    return trial ? &sc->trialElastic : &sc->elastic;
  }
  // At Newton's iterate: the element pass with the stiffness, written into `gradient`. With
  // `reuse`, the accepted trial's gradient and scalars (the line search evaluated them there).
  void atIterate(FrameData<Exec>&, const double* y, bool reuse, double* gradient) {
    FrameScalars* sc = d_.sc();
    if (reuse) {
      ex_.copy(gradient, d_.acceptedGrad.data(), 3 * d_.n);
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
        sc->elastic = sc->trialElastic;
        sc->inverted = sc->trialInverted;
      });
      return;
    }
    // A local pass gathers the region's corners only: the rest of the gradient is x's.
    if (d_.local) ex_.copy(gradient, d_.acceptedGrad.data(), 3 * d_.n);
    evaluate(y, true, gradient, &sc->elastic, &sc->inverted);
  }
  // At a trial: energies and inversions, the gradient kept in trialGrad (an accepted trial's is
  // the next iterate's, acceptedGrad).
  void atTrial(FrameData<Exec>&, const double* y, const std::uint8_t* only, double* gradient) {
    FrameScalars* sc = d_.sc();
    evaluate(y, false, d_.trialGrad.data(), &sc->trialElastic, &sc->trialInverted, only);
    if (gradient) ex_.copy(gradient, d_.trialGrad.data(), 3 * d_.n);  // acceptedGrad, accepted
  }
  void atAccepted(FrameData<Exec>&, const double*, double* gradient) {
    ex_.copy(gradient, d_.acceptedGrad.data(), 3 * d_.n);
  }
  // A quarter of each element's energy to each of its corners.
  struct VertexShare {
    const int *start, *slots;
    const double* energy;
    GALSCULPT_HD void add(int v, double& sum) const {
      for (int i = start[v]; i < start[v + 1]; ++i) sum += 0.25 * energy[slots[i] / 4];
    }
  };
  VertexShare vertexShare(FrameData<Exec>&, bool trial) const {
    return {d_.vertexSlotStart.data(), d_.vertexSlots.data(),
            trial ? d_.trialEnergy.data() : d_.elemEnergy.data()};
  }
  // Its blocks are gathered into the stiffness (evaluate): none added on the diagonal.
  struct Blocks {
    GALSCULPT_HD void add(int, const double*, double*) const {}
  };
  Blocks diagonalBlocks(FrameData<Exec>&) const { return {}; }

  // ---- the element pass ---------------------------------------------------------------------

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
  void evaluate(const double* y, bool withHessian, double* gradient, double* energyOut,
                double* invertedOut, const std::uint8_t* only = nullptr) {
    const std::uint8_t* touched = nullptr;
    if (!only) {
      only = d_.evaluated();
      touched = d_.touched();
    }
    const ElementInputs in = inputs();
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

  // What the element kernels read of the frame: tets, edges, damage, rest shapes, plasticity.
  ElementInputs inputs() const {
    return {d_.tetVertices.data(), d_.tetEdges.data(), d_.damaged.data(), d_.rest.data(),
            plastic_.shapes(),     plastic_.shaped(),  d_.removed.data(), plastic_.strain()};
  }

 private:
  Exec& ex_;
  const SimModel& model_;
  FrameData<Exec>& d_;
  const PlasticState<Exec>& plastic_;
  std::unique_ptr<StiffnessGather> hostGather_;  // host memory only
};

}  // namespace galsculpt
