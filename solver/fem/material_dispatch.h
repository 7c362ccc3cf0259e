// withMaterial: the one place in the solver that names the material models case by case (the
// number type double's operations the models ask for are eigen_svd.h's ScalarMath). Included only
// where a model is evaluated (material_kernels.h, element_lanes_body.h); the names are
// material_table.h's.
#pragma once

#include <cmath>

#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"
#include "solver/fem/materials/corotational.h"
#include "solver/fem/materials/fixed_corotated.h"
#include "solver/fem/materials/hencky.h"
#include "solver/fem/materials/stable_neo_hookean.h"
#include "solver/fem/materials/stvk.h"

namespace galsculpt::kernels {

// f(Model{}) for the model's type.
template <typename F>
GALSCULPT_HD decltype(auto) withMaterial(MaterialModel model, F&& f) {
  switch (model) {
    case MaterialModel::Corotational:
      return f(Corotational{});
    case MaterialModel::StVK:
      return f(StVK{});
    case MaterialModel::FixedCorotated:
      return f(FixedCorotated{});
    case MaterialModel::Hencky:
      return f(Hencky{});
    case MaterialModel::StableNeoHookean:
      break;
  }
  return f(StableNeoHookean{});
}

}  // namespace galsculpt::kernels
