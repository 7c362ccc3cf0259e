#include "solver/fem/tet_element.h"

#include <stdexcept>

#include "solver/fem/material_kernels.h"

// Every function here converts to plain arrays and calls the shared element kernels
// (element_kernels.h), which the CUDA backend runs too.
namespace galsculpt {

namespace {

kernels::M3 toM3(const Eigen::Matrix3d& m) {
  kernels::M3 out;
  for (int i = 0; i < 9; ++i) out.a[i] = m.data()[i];
  return out;
}

Eigen::Matrix3d fromM3(const kernels::M3& m) {
  return Eigen::Map<const Eigen::Matrix3d>(m.a);
}

std::array<double, 12> flatPoints(const TetPoints& x) {
  std::array<double, 12> out;
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 3; ++k) out[3 * a + k] = x[a][k];
  return out;
}

kernels::Hessian kernelMode(HessianMode mode) {
  switch (mode) {
    case HessianMode::None:
      return kernels::Hessian::None;
    case HessianMode::Exact:
      return kernels::Hessian::Exact;
    case HessianMode::ProjectedSpd:
      break;
  }
  return kernels::Hessian::ProjectedSpd;
}

}  // namespace

TetRest computeTetRest(const TetPoints& p) {
  TetRest r;
  if (!kernels::computeRest(flatPoints(p).data(), r))
    throw std::invalid_argument("degenerate rest tet");
  return r;
}

Eigen::Matrix3d deformationGradient(const TetRest& rest, const TetPoints& x) {
  return fromM3(kernels::deformationGradient(rest, flatPoints(x).data()));
}

Eigen::Matrix3d firstPiolaStress(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f) {
  return fromM3(kernels::firstPiolaStress(model, lame, toM3(f)));
}

Mat9 stressDerivative(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f,
                      bool projectSpd) {
  Mat9 h;
  kernels::stressDerivative(model, lame, toM3(f), projectSpd, h.data());
  return h;
}

void evaluateEdgeStrainElement(const Lame& lame, const TetRest& rest, const TetPoints& x,
                               const EdgeDamage& damage, HessianMode mode, ElementEval& out) {
  kernels::evaluateEdgeStrainElement(lame, rest, flatPoints(x).data(), damage.intact,
                                     damage.compressionResists, kernelMode(mode), out.energy,
                                     out.gradient.data(), out.hessian.data());
}

void evaluateElement(MaterialModel model, const Lame& lame, const TetRest& rest, const TetPoints& x,
                     const EdgeDamage& damage, HessianMode mode, ElementEval& out) {
  kernels::evaluateElement(model, lame, rest, flatPoints(x).data(), damage.intact,
                           damage.compressionResists, kernelMode(mode), out.energy,
                           out.gradient.data(), out.hessian.data());
}

std::array<double, 6> edgeNormalStress(MaterialModel model, const Lame& lame, const TetRest& rest,
                                       const TetPoints& x, const EdgeDamage& damage) {
  std::array<double, 6> out{};
  kernels::edgeNormalStress(model, lame, rest, flatPoints(x).data(), damage.intact,
                            damage.compressionResists, out.data());
  return out;
}

}  // namespace galsculpt
