// The plastic state of a clay body on an executor (docs/physics.md, "Plasticity"): each
// element's inverse plastic deformation Fp^-1 and accumulated strain, the plastic rest shapes
// the element pass reads (the rest shape Fp maps to, for the elements whose Fp is not the
// identity), a copy to roll a failed sub-step back, and the return map applied after each
// sub-step (damaged elements do not flow). Active only when the state carries a plastic state.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fem/dense_kernels.h"
#include "solver/fem/element_kernels.h"
#include "solver/fem/material_table.h"
#include "solver/frame/element_pass.h"
#include "solver/frame/host_shadow.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class PlasticState {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  PlasticState(const Exec& ex, const SimModel& model)
      : ex_(ex), model_(model), tets_(model.numTets()) {
    count_.resize(1);
  }

  bool active() const { return active_; }
  // Whether an element flowed since the last syncIn (the host's state is then stale).
  bool flowed() const { return flowed_; }

  // Brings the executor's copy up to date with `state`; true when the rest shapes changed.
  bool syncIn(const SimState& state, const kernels::RestData* rest) {
    active_ = !state.plasticInverse.empty();
    if (!active_) return false;
    if (shape_.size() != static_cast<size_t>(tets_)) {
      shape_.resize(tets_);
      shaped_.resize(tets_);
      hostFp_.clear();  // the shapes are computed below
    }
    bool changed = false;
    if (uploadIfChanged(state.plasticInverse, hostFp_, fp_)) {
      refreshShapes(rest, nullptr);
      changed = true;
    }
    uploadIfChanged(state.plasticStrain, hostStrain_, strain_);
    if (savedFp_.size() != fp_.size()) {
      savedFp_.resize(fp_.size());
      savedStrain_.resize(strain_.size());
    }
    flowed_ = false;
    return changed;
  }
  // Writes the plastic state back when an element flowed (otherwise the host's is the device's).
  void syncOut(SimState& state) {
    if (!flowed_) return;
    downloadThroughShadows(ex_, fp_, hostFp_, state.plasticInverse, strain_, hostStrain_,
                           state.plasticStrain);
  }
  void save() {
    if (!active_) return;
    ex_.copy(savedFp_.data(), fp_.data(), 9 * static_cast<size_t>(tets_));
    ex_.copy(savedStrain_.data(), strain_.data(), tets_);
  }
  void restore(const kernels::RestData* rest) {
    if (!active_) return;
    ex_.copy(fp_.data(), savedFp_.data(), 9 * static_cast<size_t>(tets_));
    refreshShapes(rest, nullptr);
    ex_.copy(strain_.data(), savedStrain_.data(), tets_);
  }

  // What the element pass reads (null when not active).
  const kernels::RestData* shapes() const { return active_ ? shape_.data() : nullptr; }
  const std::uint8_t* shaped() const { return active_ ? shaped_.data() : nullptr; }
  // Each element's accumulated plastic strain (null when not active).
  const double* strain() const { return active_ ? strain_.data() : nullptr; }
  // Fp^-1 in the executor's memory (what captured sections bake in).
  const double* inverse() const { return fp_.data(); }

  // The plastic rest shapes of the elements (all, or those with flowed[t] > 0) from Fp^-1.
  void refreshShapes(const kernels::RestData* rest, const double* flowed) {
    const double* fp = fp_.data();
    kernels::RestData* shape = shape_.data();
    std::uint8_t* shaped = shaped_.data();
    ex_.forEach(tets_, [=] GALSCULPT_LAMBDA(int t) {
      if (flowed && !(flowed[t] > 0.0)) return;
      shaped[t] = 0;
      if (ElementInputs::isIdentity(fp + 9 * t)) return;
      kernels::M3 f;
      for (int i = 0; i < 9; ++i) f.a[i] = fp[9 * t + i];
      shaped[t] = kernels::plasticRest(rest[t], f, shape[t]) ? 1 : 0;
    });
  }

  // The return map at positions x after a sub-step: every undamaged element's Fp^-1 and
  // strain, its rest shape again where it flowed (`flowed`: scratch, one per element). How many
  // flowed.
  int returnMap(const double* x, const std::uint8_t* damaged, const int* tv, const int* te,
                const kernels::RestData* rest, double* flowed) {
    double* fp = fp_.data();
    double* strain = strain_.data();
    const Lame lame = model_.material.lame;
    const kernels::PlasticParamsData params{model_.material.plastic.yieldStress,
                                            model_.material.plastic.hardening,
                                            materialInfo(model_.material.model).flowInEnergy};
    ex_.forEach(tets_, [=] GALSCULPT_LAMBDA(int t) {
      flowed[t] = 0.0;
      for (int k = 0; k < 6; ++k)
        if (damaged[te[6 * t + k]]) return;
      double x12[12];
      for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k) x12[3 * a + k] = x[3 * tv[4 * t + a] + k];
      const kernels::M3 f = kernels::deformationGradient(rest[t], x12);
      kernels::M3 inv;
      for (int i = 0; i < 9; ++i) inv.a[i] = fp[9 * t + i];
      const bool flow = kernels::plasticReturn(lame, params, f, inv, strain[t]);
      if (flow)
        for (int i = 0; i < 9; ++i) fp[9 * t + i] = inv.a[i];
      flowed[t] = flow ? 1.0 : 0.0;
    });
    refreshShapes(rest, flowed);
    ex_.sum(
        tets_, [=] GALSCULPT_LAMBDA(int t) { return flowed[t]; }, count_.data());
    double count = 0.0;
    ex_.read(count_.data(), &count, 1);
    flowed_ = flowed_ || count > 0.0;
    return static_cast<int>(count);
  }

 private:
  const Exec& ex_;
  const SimModel& model_;
  int tets_ = 0;
  bool active_ = false, flowed_ = false;
  Buffer<double> fp_, strain_, savedFp_, savedStrain_, count_;
  Buffer<kernels::RestData> shape_;  // refreshShapes
  Buffer<std::uint8_t> shaped_;
  std::vector<double> hostFp_, hostStrain_;  // what the executor holds
};

}  // namespace galsculpt
