// The material model and Lame parameters as plain types: shared by the CPU solver and the CUDA
// kernels (no Eigen, nothing a device compiler cannot take).
#pragma once

namespace galsculpt {

// The models (solver/fem/material_table.h lists them; solver/fem/materials/ defines them).
enum class MaterialModel { Corotational, StVK, StableNeoHookean, FixedCorotated, Hencky };

// The crack faces' closing width a model takes unless told (MaterialParams::crackWidth, the
// scene's fracture.crack_width): the smooth closing law (crack_law.h); 0 is the hard law.
constexpr double kDefaultCrackWidth = 0.01;

struct Lame {
  double mu = 0.0;      // shear modulus (Pa)
  double lambda = 0.0;  // first Lame parameter (Pa)
  // For a model whose energy includes its plastic flow (materialInfo(model).flowInEnergy): the
  // element's von Mises yield stress at the step's start (Pa; 0: elastic) and the hardening
  // modulus. The frame sets them per element from its plastic strain (ElementInputs::lame).
  double yield = 0.0;
  double hardening = 0.0;
  // How far a damaged edge's crack faces may press into each other (a strain) under the smooth
  // closing law (crack_law.h); 0: the hard law, the faces resisting with the whole stiffness at
  // contact. A property of the damaged material, fixed for a run (MaterialParams::crackWidth).
  double crackWidth = 0.0;
};

}  // namespace galsculpt
