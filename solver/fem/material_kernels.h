// What evaluates an element's material model, compiled for both the CPU and the GPU: Psi and its
// derivatives in the singular values through the model's file (material_dispatch.h), the first
// Piola-Kirchhoff stress and dP/dF, one element's energy, force and stiffness (intact: the model;
// with damaged edges: the edge-strain form of element_kernels.h) and the edge normal stresses of
// the fracture pass. Only the translation units that evaluate elements include it (the element
// launches of each executor, element_lanes_*.cpp, tet_element.cpp, isotropic_material.cpp), so an
// edit of a model recompiles those and not the frame.
#pragma once

#include <cstdint>

#include "solver/fem/element_kernels.h"
#include "solver/fem/material_dispatch.h"

namespace galsculpt::kernels {

GALSCULPT_HD SingularValueEnergy singularValueEnergy(MaterialModel model, const Lame& lame,
                                                     const double s[3]) {
  SingularValueEnergy out;
  double hessian[3][3];
  withMaterial(model, [&](auto m) {
    decltype(m)::template singularValues<double, ScalarMath>(lame, s, out.energy, out.gradient,
                                                             hessian);
  });
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.hessian(i, j) = hessian[i][j];
  return out;
}

GALSCULPT_HD M3 firstPiolaStress(MaterialModel model, const Lame& lame, const M3& f) {
  M3 u, v;
  double s[3];
  rotationVariantSvd(f, u, s, v);
  const SingularValueEnergy e = singularValueEnergy(model, lame, s);
  return scaledProduct(u, e.gradient, v);
}

GALSCULPT_HD void stressDerivative(MaterialModel model, const Lame& lame, const M3& f,
                                   bool projectSpd, double h[81]) {
  M3 u, v;
  double s[3];
  rotationVariantSvd(f, u, s, v);
  eigenSystemHessian(u, s, v, singularValueEnergy(model, lame, s), projectSpd, h);
}

// Whether the model has Psi and P in closed form in F (directStress), without an SVD.
GALSCULPT_HD bool hasDirectStress(MaterialModel model) {
  return withMaterial(model, [](auto m) { return decltype(m)::kDirect; });
}

// Psi and P straight from F where the model has them in closed form (hasDirectStress; the
// energy-only evaluations of the line search use it), through the SVD otherwise.
GALSCULPT_HD M3 directStress(MaterialModel model, const Lame& lame, const M3& f, double& psi) {
  return withMaterial(model, [&](auto m) {
    if constexpr (decltype(m)::kDirect) {
      return decltype(m)::direct(lame, f, psi);
    } else {
      M3 u, v;
      double s[3];
      rotationVariantSvd(f, u, s, v);
      const SingularValueEnergy e = singularValueEnergy(model, lame, s);
      psi = e.energy;
      return scaledProduct(u, e.gradient, v);
    }
  });
}

// Energy, gradient and (unless mode is None) the 12x12 Hessian of one element: the model itself
// when intact, the edge-strain form when any edge is damaged. `opened`, when not null, gets the
// damaged edges whose cracks are open (none when intact).
GALSCULPT_HD void evaluateElement(MaterialModel model, const Lame& lame, const RestData& rest,
                                  const double x[12], std::uint8_t intact, bool compressionResists,
                                  Hessian mode, double& energy, double gradient[12],
                                  double* hessian, std::uint8_t* opened = nullptr) {
  if (intact != kIntact) {
    evaluateEdgeStrainElement(lame, rest, x, intact, compressionResists, mode, energy, gradient,
                              hessian, opened);
    return;
  }
  if (opened) *opened = 0;
  const M3 f = deformationGradient(rest, x);
  double c[4][3];
  shapeGradients(rest, c);
  M3 p;
  M3 u, v;
  double s[3];
  SingularValueEnergy e;
  if (mode == Hessian::None && hasDirectStress(model)) {
    double psi = 0.0;
    p = directStress(model, lame, f, psi);
    energy = rest.volume * psi;
  } else {
    rotationVariantSvd(f, u, s, v);
    e = singularValueEnergy(model, lame, s);
    p = scaledProduct(u, e.gradient, v);
    energy = rest.volume * e.energy;
  }
  elementForceOf(rest.volume, p, c, gradient);
  if (mode == Hessian::None) return;
  // K = V sum lambda (dF/dx^T vec Q)(dF/dx^T vec Q)^T over the modes Q of dP/dF, with
  // dF/dx^T vec Q = [Q c_0; Q c_1; Q c_2; Q c_3]: 12-vectors instead of the 9x9 dP/dF.
  for (int i = 0; i < 144; ++i) hessian[i] = 0.0;
  const bool project = mode == Hessian::ProjectedSpd;
  forEachStressMode(u, s, v, e, [&](double lambda, const M3& q) {
    if (project) lambda = fmax(lambda, 0.0);
    if (lambda == 0.0) return;
    double w[12];
    modeVectorOf(q, c, w);
    const double scale = rest.volume * lambda;
    for (int col = 0; col < 12; ++col) {
      const double wc = scale * w[col];
      for (int row = 0; row <= col; ++row) hessian[row + 12 * col] += wc * w[row];
    }
  });
  for (int col = 0; col < 12; ++col)
    for (int row = col + 1; row < 12; ++row) hessian[row + 12 * col] = hessian[col + 12 * row];
}

// Normal stress n^T sigma n along each edge (current direction n, Cauchy stress sigma): what
// the fracture pass compares with its threshold.
GALSCULPT_HD void edgeNormalStress(MaterialModel model, const Lame& lame, const RestData& rest,
                                   const double x[12], std::uint8_t intact, bool compressionResists,
                                   double out[6]) {
  const M3 f = deformationGradient(rest, x);
  M3 p;
  if (intact == kIntact) {
    p = firstPiolaStress(model, lame, f);
  } else {
    double d[6][3], strain[6];
    edgeGreenStrains(rest, x, d, strain);
    CrackedStrainState state;
    crackedStrainState(lame, rest, strain, intact, compressionResists, false, state);
    double v[6];  // (E11,E22,E33,E12,E13,E23) of the elastic strain
    for (int r = 0; r < 6; ++r) {
      v[r] = 0.0;
      for (int c = 0; c < 6; ++c) v[r] += rest.strainFromEdges[r + 6 * c] * state.z[c];
    }
    M3 e{};
    e(0, 0) = v[0], e(1, 1) = v[1], e(2, 2) = v[2];
    e(0, 1) = e(1, 0) = v[3], e(0, 2) = e(2, 0) = v[4], e(1, 2) = e(2, 1) = v[5];
    const double trace = v[0] + v[1] + v[2];
    M3 s = e;
    for (int i = 0; i < 9; ++i) s.a[i] *= 2.0 * lame.mu;
    for (int i = 0; i < 3; ++i) s(i, i) += lame.lambda * trace;
    p = multiply(f, s);
  }
  const double j = determinant(f);
  // A collapsed or inverted element keeps the Piola-Kirchhoff scale instead of dividing by a
  // vanishing or negative volume ratio.
  M3 sigma = multiply(p, transpose(f));
  const double scale = j > 1e-6 ? 1.0 / j : 1.0;
  for (int e = 0; e < 6; ++e) {
    const int a = edgeVertex(e, 0), b = edgeVertex(e, 1);
    double n[3], len2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      n[k] = x[3 * b + k] - x[3 * a + k];
      len2 += n[k] * n[k];
    }
    const double len = sqrt(len2);
    double value = 0.0;
    if (len > 0.0) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) value += n[r] * sigma(r, c) * n[c];
      value *= scale / len2;
    }
    out[e] = value;
  }
}

}  // namespace galsculpt::kernels
