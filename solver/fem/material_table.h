// The material models, one row each: the table the scene reader, the Scene panel and
// docs/scenes.md list (names and summaries). Each model is a file under solver/fem/materials/:
// its energy density, gradient and Hessian in the singular values of F, templated on the number
// type (double in the scalar and CUDA kernels, a SIMD lane of doubles in element_lanes_body.h)
// so that every path runs the same source, and, where Psi and P have a closed form in F
// (kDirect), `direct` for the energy-only evaluations. Adding a model: its file, its value in
// material_types.h, its row below and its case in material_dispatch.h's withMaterial
// (tests/solver/fem/material_table_test.cpp checks every row by finite differences). The rows
// name no model's file: the reader and the panel do not recompile when a model changes.
#pragma once

#include "solver/fem/material_types.h"

namespace galsculpt {

struct MaterialInfo {
  MaterialModel model;
  const char* name;     // in scenes ("material": {"model": NAME}) and the Scene panel
  const char* summary;  // one line for the panel's tooltip and docs/scenes.md
  // Whether the model's energy includes von Mises flow (a yield stress then makes each Newton
  // iteration minimize over the step's flow); with another model the flow is applied after the
  // step converged.
  bool flowInEnergy = false;
};

inline constexpr MaterialInfo kMaterialModels[] = {
    {MaterialModel::Corotational, "corotational",
     "linear corotational: stiff and simple, soft in volume under strong compression"},
    {MaterialModel::StVK, "stvk",
     "St. Venant-Kirchhoff: Green strain; softens and can invert under strong compression"},
    {MaterialModel::StableNeoHookean, "stable_neo_hookean",
     "stable neo-Hookean (Smith et al. 2018): well posed in compression and through inversion"},
    {MaterialModel::FixedCorotated, "fixed_corotated",
     "fixed corotated (Stomakhin et al. 2012): corotational with a volume term in J"},
    {MaterialModel::Hencky, "hencky",
     "Hencky (logarithmic strain): its plastic flow solved with the step, for clay and flesh",
     true},
};

// The row of `model` (every model has one).
inline const MaterialInfo& materialInfo(MaterialModel model) {
  for (const MaterialInfo& m : kMaterialModels)
    if (m.model == model) return m;
  return kMaterialModels[0];
}

}  // namespace galsculpt
