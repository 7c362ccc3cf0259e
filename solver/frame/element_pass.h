// One element pass's per-element work (FrameSolver::elementPass): what a thread needs to set an
// element up (ElementInputs), the pass's inputs and outputs with the scalar kernel's evaluation
// (ElementPass, the same on the CPU and the GPU), and on the CPU the pass over the SIMD lanes
// of element_lanes.h (elementPassInLanes).
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

// One element's gradient at positions y, without its stiffness (the pieces' start).
struct ElementGradient {
  ElementInputs in;
  MaterialModel model;
  Lame lame;
  bool resists;
  GALSCULPT_HD void operator()(int t, const double* y, double* gradient) const {
    double x12[12], energy;
    std::uint8_t intact;
    const kernels::RestData& r = in.load(t, y, x12, intact);
    kernels::evaluateElement(model, lame, r, x12, intact, in.resists(t, resists),
                             kernels::Hessian::None, energy, gradient, nullptr);
  }
};

// One element pass's inputs and outputs (IncrementalPotential::elementPass), copied into its
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
  const std::uint8_t* only;  // (nTets) or null: the elements to evaluate
  static constexpr int kPackedHessian = 90;

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

  // Element t by the scalar kernel.
  GALSCULPT_HD void evaluate(int t, const double x12[12], std::uint8_t intact,
                             const kernels::RestData& r, kernels::Hessian elementMode) const {
    double hess[144];
    kernels::evaluateElement(model, lame, r, x12, intact, in.resists(t, resists), elementMode,
                             energy[t], gradient + 12 * t, hess, opened + t);
    if (elementMode != kernels::Hessian::None && !zeroStiffness(opened[t]))
      pack(hess, packedHessian + kPackedHessian * static_cast<size_t>(t));
  }

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

// The pass on the CPU's SIMD lanes: sixteen consecutive elements per item; the intact ones whose
// stiffness is wanted go through `lanes` four at a time, the damaged ones (but those holding two
// pieces) through `crackedLanes`; the rest, and those the lanes hand back, through the scalar
// kernel. Either kernel may be null (its elements then take the scalar kernel). The lanes
// compute the scalar kernel's bits, so which elements share a group changes nothing.
template <typename Exec>
void elementPassInLanes(Exec& ex, const ElementPass& pass, int tets, kernels::LaneKernel lanes,
                        kernels::CrackedLaneKernel crackedLanes) {
  constexpr int kGroup = 4 * kernels::kLanes;
  constexpr int kPacked = ElementPass::kPackedHessian;
  const int groups = (tets + kGroup - 1) / kGroup;
  ex.forEach(
      groups,
      [=](int g) {
        kernels::LaneInputs intactIn;
        kernels::LaneOutputs intactOut;
        int intactTet[kernels::kLanes];
        kernels::CrackedLaneInputs crackedIn;
        kernels::LaneOutputs crackedOut;
        int crackedTet[kernels::kLanes];
        auto flushIntact = [&] {
          const unsigned back = lanes(pass.model, pass.lame, intactIn, intactOut);
          for (int l = 0; l < intactIn.count; ++l)
            if (back >> l & 1u)
              pass.evaluate(intactTet[l], intactIn.x[l], kernels::kIntact, *intactIn.rest[l],
                            kernels::Hessian::ProjectedSpd);
          intactIn.count = 0;
        };
        auto flushCracked = [&] {
          const unsigned back = crackedLanes(pass.lame, crackedIn, crackedOut);
          for (int l = 0; l < crackedIn.count; ++l)
            if (back >> l & 1u)
              pass.evaluate(crackedTet[l], crackedIn.x[l], crackedIn.intact[l], *crackedIn.rest[l],
                            kernels::Hessian::ProjectedSpd);
          crackedIn.count = 0;
        };
        const int end = std::min(tets, kGroup * (g + 1));
        for (int t = kGroup * g; t < end; ++t) {
          double x12[12];
          std::uint8_t intact;
          const kernels::RestData* r;
          kernels::Hessian mode;
          if (!pass.prepare(t, x12, intact, r, mode)) continue;
          const bool stiffness = mode == kernels::Hessian::ProjectedSpd;
          if (intact == kernels::kIntact && lanes && stiffness) {
            const int l = intactIn.count++;
            intactTet[l] = t;
            intactIn.rest[l] = r;
            std::memcpy(intactIn.x[l], x12, sizeof x12);
            intactOut.energy[l] = pass.energy + t;
            intactOut.gradient[l] = pass.gradient + 12 * t;
            intactOut.packedHessian[l] = pass.packedHessian + kPacked * static_cast<size_t>(t);
            if (intactIn.count == kernels::kLanes) flushIntact();
          } else if (intact != kernels::kIntact && crackedLanes && stiffness &&
                     !kernels::holdsTwoPieces(intact)) {
            const int l = crackedIn.count++;
            crackedTet[l] = t;
            crackedIn.rest[l] = r;
            std::memcpy(crackedIn.x[l], x12, sizeof x12);
            crackedIn.intact[l] = intact;
            crackedIn.resists[l] = pass.in.resists(t, pass.resists);
            crackedOut.energy[l] = pass.energy + t;
            crackedOut.gradient[l] = pass.gradient + 12 * t;
            crackedOut.packedHessian[l] = pass.packedHessian + kPacked * static_cast<size_t>(t);
            crackedOut.opened[l] = pass.opened + t;
            if (crackedIn.count == kernels::kLanes) flushCracked();
          } else {
            pass.evaluate(t, x12, intact, *r, mode);
          }
        }
        if (intactIn.count > 0) flushIntact();
        if (crackedIn.count > 0) flushCracked();
      },
      kGroup);
}

}  // namespace galsculpt
