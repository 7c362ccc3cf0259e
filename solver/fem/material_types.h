// The material model and Lame parameters as plain types: shared by the CPU solver and the CUDA
// kernels (no Eigen, nothing a device compiler cannot take).
#pragma once

namespace galsculpt {

// The models (solver/fem/material_table.h lists them; solver/fem/materials/ defines them).
enum class MaterialModel { Corotational, StVK, StableNeoHookean, FixedCorotated };

struct Lame {
  double mu = 0.0;      // shear modulus (Pa)
  double lambda = 0.0;  // first Lame parameter (Pa)
};

}  // namespace galsculpt
