// The launches that evaluate an element's material model, declared in element_pass.h and
// accelerated_start.h. Included only by the translation units that instantiate them for an
// executor (solver/frame/cpu_element_launches.cpp, gpu/cuda_element_launches.cu, and a test's
// own executor): the frame calls them without seeing a model.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "solver/fem/element_lanes.h"
#include "solver/fem/material_kernels.h"
#include "solver/frame/accelerated_start.h"
#include "solver/frame/element_pass.h"

namespace galsculpt {

// Element t of `pass` by the scalar kernel.
GALSCULPT_HD void evaluateInPass(const ElementPass& pass, int t, const double x12[12],
                                 std::uint8_t intact, const kernels::RestData& r,
                                 kernels::Hessian elementMode) {
  double hess[144];
  kernels::evaluateElement(pass.model, pass.in.lame(t, pass.lame), r, x12, intact,
                           pass.in.resists(t, pass.resists), elementMode, pass.energy[t],
                           pass.gradient + 12 * t, hess, pass.opened + t);
  if (elementMode != kernels::Hessian::None && !ElementPass::zeroStiffness(pass.opened[t]))
    ElementPass::pack(hess,
                      pass.packedHessian + ElementPass::kPackedHessian * static_cast<size_t>(t));
}

// The pass on the CPU's SIMD lanes: sixteen consecutive elements per item; the intact ones go
// through `lanes` four at a time (those whose stiffness is wanted apart from those whose is not,
// where the model has no closed-form stress),
// the damaged ones whose stiffness is wanted (but those holding two pieces) through
// `crackedLanes`; the rest, and those the lanes hand back, through the scalar kernel. Either kernel
// may be null (its elements then take the scalar kernel). The lanes compute the scalar kernel's
// bits, so which elements share a group changes nothing.
template <typename Exec>
void elementPassInLanes(Exec& ex, const ElementPass& pass, int tets, kernels::LaneKernel lanes,
                        kernels::CrackedLaneKernel crackedLanes) {
  constexpr int kGroup = 4 * kernels::kLanes;
  constexpr int kPacked = ElementPass::kPackedHessian;
  const int groups = (tets + kGroup - 1) / kGroup;
  // Without the stiffness a model with its stress in closed form in F takes that, not the SVD
  // the lanes take (material_kernels.h: another algorithm, other bits): the scalar kernel's.
  const bool forceLanes = !kernels::hasDirectStress(pass.model);
  ex.forEach(
      groups,
      [=](int g) {
        // Intact elements in two sets of lanes: [1] with their stiffness, [0] without (a trial's,
        // or a kept stiffness's).
        kernels::LaneInputs intactIn[2];
        kernels::LaneOutputs intactOut[2];
        int intactTet[2][kernels::kLanes];
        intactIn[0].stiffness = false;
        kernels::CrackedLaneInputs crackedIn;
        kernels::LaneOutputs crackedOut;
        int crackedTet[kernels::kLanes];
        auto flushIntact = [&](int k) {
          const unsigned back = lanes(pass.model, pass.lame, intactIn[k], intactOut[k]);
          for (int l = 0; l < intactIn[k].count; ++l)
            if (back >> l & 1u)
              evaluateInPass(pass, intactTet[k][l], intactIn[k].x[l], kernels::kIntact,
                             *intactIn[k].rest[l],
                             k ? kernels::Hessian::ProjectedSpd : kernels::Hessian::None);
          intactIn[k].count = 0;
        };
        auto flushCracked = [&] {
          const unsigned back = crackedLanes(pass.lame, crackedIn, crackedOut);
          for (int l = 0; l < crackedIn.count; ++l)
            if (back >> l & 1u)
              evaluateInPass(pass, crackedTet[l], crackedIn.x[l], crackedIn.intact[l],
                             *crackedIn.rest[l], kernels::Hessian::ProjectedSpd);
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
          if (intact == kernels::kIntact && lanes && (stiffness || forceLanes)) {
            const int k = stiffness ? 1 : 0;
            kernels::LaneInputs& in = intactIn[k];
            kernels::LaneOutputs& out = intactOut[k];
            const int l = in.count++;
            intactTet[k][l] = t;
            in.rest[l] = r;
            in.yield[l] = pass.in.lame(t, pass.lame).yield;
            std::memcpy(in.x[l], x12, sizeof x12);
            out.energy[l] = pass.energy + t;
            out.gradient[l] = pass.gradient + 12 * t;
            out.packedHessian[l] =
                stiffness ? pass.packedHessian + kPacked * static_cast<size_t>(t) : nullptr;
            if (in.count == kernels::kLanes) flushIntact(k);
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
            evaluateInPass(pass, t, x12, intact, *r, mode);
          }
        }
        for (int k = 0; k < 2; ++k)
          if (intactIn[k].count > 0) flushIntact(k);
        if (crackedIn.count > 0) flushCracked();
      },
      kGroup);
}

template <typename Exec>
void launchElementPass(const Exec& ex, const ElementPass& pass, int tets, kernels::LaneKernel lanes,
                       kernels::CrackedLaneKernel crackedLanes) {
  if constexpr (Exec::kHostMemory) {
    if (lanes != nullptr || crackedLanes != nullptr) {
      elementPassInLanes(ex, pass, tets, lanes, crackedLanes);
      return;
    }
  }
  ex.forEach(tets, [=] GALSCULPT_LAMBDA(int t) {
    double x12[12];
    std::uint8_t intact;
    const kernels::RestData* r;
    kernels::Hessian elementMode;
    if (pass.prepare(t, x12, intact, r, elementMode))
      evaluateInPass(pass, t, x12, intact, *r, elementMode);
  });
}

template <typename Exec>
void launchElementGradients(const Exec& ex, const ElementModel& element,
                            const SharedElements& shared, int count, const double* y, double* out) {
  ex.forEach(count, [=] GALSCULPT_LAMBDA(int i) {
    if (!shared.read(i)) return;
    double x12[12], energy;
    std::uint8_t intact;
    const int t = shared.tets[i];
    const kernels::RestData& r = element.in.load(t, y, x12, intact);
    kernels::evaluateElement(element.model, element.in.lame(t, element.lame), r, x12, intact,
                             element.in.resists(t, element.resists), kernels::Hessian::None, energy,
                             out + 12 * i, nullptr);
  });
}

template <typename Exec>
void launchEdgeNormalStress(const Exec& ex, const ElementModel& element, int tets, const double* x,
                            double* slot) {
  ex.forEach(tets, [=] GALSCULPT_LAMBDA(int t) {
    double x12[12];
    std::uint8_t intact;
    const kernels::RestData& r = element.in.load(t, x, x12, intact);
    kernels::edgeNormalStress(element.model, element.in.lame(t, element.lame), r, x12, intact,
                              element.in.resists(t, element.resists), slot + 6 * t);
  });
}

// Instantiates every launch for the executor Exec (in the one translation unit that does).
#define GALSCULPT_INSTANTIATE_ELEMENT_LAUNCHES(Exec)                                               \
  template void launchElementPass<Exec>(const Exec&, const ElementPass&, int, kernels::LaneKernel, \
                                        kernels::CrackedLaneKernel);                               \
  template void launchElementGradients<Exec>(const Exec&, const ElementModel&,                     \
                                             const SharedElements&, int, const double*, double*);  \
  template void launchEdgeNormalStress<Exec>(const Exec&, const ElementModel&, int, const double*, \
                                             double*)

}  // namespace galsculpt
