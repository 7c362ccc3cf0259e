// One element pass's per-element work (ElasticTerm::evaluate): what a thread needs to set an
// element up (ElementInputs), the pass's inputs and outputs (ElementPass, the same on the CPU and
// the GPU), and the launches that evaluate the material model. Those are only declared here:
// element_launches.h defines them, and each executor's own translation unit instantiates them
// (cpu_element_launches.cpp, gpu/cuda_element_launches.cu), so the frame's translation units do
// not include a material model and an edit of one recompiles the launches, not the frame.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "solver/fem/element_kernels.h"
#include "solver/fem/element_lanes.h"
#include "solver/fem/material_types.h"

namespace galsculpt {

// What one thread needs to set an element up: its corners' positions, its intact-edge mask
// and its rest data (the plastic rest shape where it has flowed). Plain pointers: captured by
// value into the element, plasticity and fracture launches.
struct ElementInputs {
  const int* tetVertices;                 // (4 nTets)
  const int* tetEdges;                    // (6 nTets)
  const std::uint8_t* damaged;            // (nEdges)
  const kernels::RestData* rest;          // (nTets)
  const kernels::RestData* plasticShape;  // (nTets) or null: elastic
  const std::uint8_t* plasticShaped;      // (nTets): 1 where plasticShape is the rest shape
  const std::uint8_t* removed;            // (nVerts) or null: 1 on removed debris
  const double* plasticStrain = nullptr;  // (nTets) or null: each element's accumulated strain

  // The rest data is returned by reference, not copied: an intact element reads 80 of its 416
  // bytes. A flowed element's plastic rest shape is computed when it flows
  // (PlasticState::refreshShapes), not at every read.
  GALSCULPT_HD const kernels::RestData& load(int t, const double* y, double x12[12],
                                             std::uint8_t& intact) const {
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) x12[3 * a + k] = y[3 * tetVertices[4 * t + a] + k];
    intact = 0;
    for (int e = 0; e < 6; ++e)
      if (!damaged[tetEdges[6 * t + e]]) intact |= static_cast<std::uint8_t>(1u << e);
    if (plasticShaped && plasticShaped[t]) return plasticShape[t];
    return rest[t];
  }
  // The material constants element t is evaluated with: `base` (the material's, its yield
  // stress set where the model's energy includes the flow) with the yield raised by the element's
  // hardening so far.
  GALSCULPT_HD Lame lame(int t, Lame base) const {
    return plasticStrain ? kernels::hardenedLame(base, plasticStrain[t]) : base;
  }
  // Whether element t's damaged edges push back when compressed: not where a corner is removed
  // debris (the rest of the body passes through where it was).
  GALSCULPT_HD bool resists(int t, bool materialResists) const {
    if (!materialResists || !removed) return materialResists;
    for (int a = 0; a < 4; ++a)
      if (removed[tetVertices[4 * t + a]]) return false;
    return true;
  }
  GALSCULPT_HD static bool isIdentity(const double* m) {
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        if (m[r + 3 * c] != (r == c ? 1.0 : 0.0)) return false;
    return true;
  }
};

// What evaluating an element's model takes besides its positions: the pieces' start's gradients
// (accelerated_start.h's launchElementGradients) and the fracture pass's edge stresses.
struct ElementModel {
  ElementInputs in;
  MaterialModel model;
  Lame lame;
  bool resists;
};

// One element pass's inputs and outputs (ElasticTerm::evaluate), copied into its
// kernels.
struct ElementPass {
  ElementInputs in;
  const double* y;
  double* energy;    // (nTets)
  double* inverted;  // (nTets) 1 where an intact element is turned inside out
  double* gradient;  // (12 nTets)
  double* packedHessian;
  MaterialModel model;
  Lame lame;
  bool resists;
  kernels::Hessian mode;
  double keep;          // kept-stiffness tolerance; 0: every stiffness evaluated
  double* keptF;        // (9 nTets) F where each kept stiffness was evaluated
  std::uint8_t* fresh;  // (nTets) 1 where the stiffness was evaluated this pass
  // (nTets) each element's open cracks (0 when intact). In the pass with stiffness, all six
  // open (zeroStiffness) also says the element's stiffness is zero and was not written.
  std::uint8_t* opened;
  const std::uint8_t* only;                 // (nTets) or null: the elements to evaluate
  static constexpr int kPackedBlocks = 10;  // an element's 3x3 blocks on and above its diagonal
  static constexpr int kPackedHessian = 9 * kPackedBlocks;

  // Loads element t and records whether it is inverted; false when `only` leaves it out.
  // `elementMode`: the stiffness it needs (none when its kept one will do).
  GALSCULPT_HD bool prepare(int t, double x12[12], std::uint8_t& intact,
                            const kernels::RestData*& r, kernels::Hessian& elementMode) const {
    if (only && !only[t]) return false;
    r = &in.load(t, y, x12, intact);
    elementMode = mode;
    if (intact != kernels::kIntact) {
      // A damaged element's stiffness switches where one of its cracks opens or closes: it is
      // evaluated every time. Its deformation gradient enters nothing: not computed.
      if (keep > 0.0) fresh[t] = 1;
      inverted[t] = 0.0;
      return true;
    }
    const kernels::M3 f = kernels::deformationGradient(*r, x12);
    if (keep > 0.0) {
      // Every entry within the tolerance; a NaN record (never evaluated, flowed) fails the
      // comparison and is evaluated (a running maximum through fmax dropped the NaN).
      bool kept = true;
      for (int i = 0; i < 9; ++i) kept = kept && fabs(f.a[i] - keptF[9 * t + i]) <= keep;
      if (kept)
        elementMode = kernels::Hessian::None;
      else
        for (int i = 0; i < 9; ++i) keptF[9 * t + i] = f.a[i];
      fresh[t] = kept ? 0 : 1;
    }
    inverted[t] = kernels::determinant(f) <= 0.0 ? 1.0 : 0.0;
    opened[t] = 0;  // the SIMD lanes do not write it
    return true;
  }

  // Whether an element's stiffness is zero exactly: every crack open, so no intact edge either
  // (the open cracks are damaged edges) and its energy, force and stiffness are all zero
  // (crackedStrainState). The state after many cuts of a crumb's interior.
  GALSCULPT_HD static bool zeroStiffness(std::uint8_t opened) { return opened == kernels::kIntact; }

  // An element's 12x12 stiffness is kept as its ten upper 3x3 blocks (a <= c, each
  // column-major): the gathers read 72 contiguous bytes per block and the buffer is 90 doubles
  // per element, not 144, which is most of what a frame moves through memory. (Floats were
  // measured: no faster on the sphere, and they break the exact translation invariance of K.)
  GALSCULPT_HD static int packedBlock(int a, int c) { return 4 * a - a * (a - 1) / 2 + (c - a); }
  GALSCULPT_HD static void pack(const double* h, double* packed) {
    for (int a = 0; a < 4; ++a)
      for (int c = a; c < 4; ++c) {
        double* blk = packed + 9 * packedBlock(a, c);
        for (int j = 0; j < 3; ++j)
          for (int r = 0; r < 3; ++r) blk[r + 3 * j] = h[(3 * a + r) + 12 * (3 * c + j)];
      }
  }
};

// The launches that evaluate the material model (element_launches.h). Every element's energy,
// gradient and, as `pass.mode` asks, stiffness: on a host executor through the SIMD lanes where
// `lanes` or `crackedLanes` is given, otherwise (and for what the lanes hand back) through the
// scalar kernel, the same bits either way.
template <typename Exec>
void launchElementPass(const Exec& ex, const ElementPass& pass, int tets, kernels::LaneKernel lanes,
                       kernels::CrackedLaneKernel crackedLanes);
// slot[6 t + k] = the normal stress along edge k of element t at x (the fracture pass).
template <typename Exec>
void launchEdgeNormalStress(const Exec& ex, const ElementModel& element, int tets, const double* x,
                            double* slot);

}  // namespace galsculpt
