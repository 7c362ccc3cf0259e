// One tetrahedron's elastic energy, force and stiffness, intact or with damaged edges.
//
// Intact elements use the chosen model exactly: Psi(F) from the singular values of F
// (isotropic_material.h); the stiffness dP/dF is assembled from its analytic eigensystem
// (3 scaling, 3 twist, 3 flip modes), so projecting it to SPD is clamping 9 eigenvalues.
//
// Elements with damaged edges use the graph-based form: the six edge Green strains
// eps_k = (|d_k|^2 - |D_k|^2) / (2 |D_k|^2) = n_k^T E n_k determine E exactly (E = B^-1 eps),
// so masking the strains of damaged edges removes exactly their contribution. The energy is
// St. Venant-Kirchhoff in the masked strain, Psi = 1/2 eps~^T K eps~ with K = B^-T C B^-1. A
// vertex whose edges are all damaged then enters no strain at all: it exerts and receives no
// elastic force. Damaged edges keep resisting compression unless told otherwise.
// docs/physics.md has the derivations. The arithmetic lives in element_kernels.h, shared with the
// CUDA backend; these are its Eigen-typed entry points.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>

#include "solver/fem/element_kernels.h"
#include "solver/fem/isotropic_material.h"

namespace galsculpt {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using TetPoints = std::array<Eigen::Vector3d, 4>;

inline constexpr std::uint8_t kAllEdgesIntact = 0x3f;

// Rest-shape data computed once per element: the shared kernels' plain struct (inverse rest
// edge matrix, rest volume, squared rest edge lengths, edge strains -> Green strain).
using TetRest = kernels::RestData;

// Throws std::invalid_argument for a degenerate (zero-volume) rest tet.
TetRest computeTetRest(const TetPoints& rest);

enum class HessianMode { None, Exact, ProjectedSpd };

struct ElementEval {
  double energy = 0.0;  // J
  Vec12 gradient;       // dEnergy/dx; the elastic force is -gradient
  Mat12 hessian;        // d2Energy/dx2 (when asked for)
};

Eigen::Matrix3d deformationGradient(const TetRest& rest, const TetPoints& x);

// First Piola-Kirchhoff stress P = dPsi/dF of an intact element.
Eigen::Matrix3d firstPiolaStress(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f);
// dP/dF (9x9, column-major vec), exact or projected to SPD.
Mat9 stressDerivative(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f,
                      bool projectSpd);

struct EdgeDamage {
  std::uint8_t intact = kAllEdgesIntact;  // bit k set: edge k (kTetEdges order) is intact
  bool compressionResists = true;         // damaged edges still push back when compressed
};

// The graph-based form alone: St. Venant-Kirchhoff in the masked edge strains. With every
// edge intact it equals the StVK model exactly. evaluateElement uses it for damaged elements.
void evaluateEdgeStrainElement(const Lame& lame, const TetRest& rest, const TetPoints& x,
                               const EdgeDamage& damage, HessianMode mode, ElementEval& out);

// Energy, gradient and (optionally) Hessian of one element: the model itself when intact, the
// graph-based form when any edge is damaged.
void evaluateElement(MaterialModel model, const Lame& lame, const TetRest& rest, const TetPoints& x,
                     const EdgeDamage& damage, HessianMode mode, ElementEval& out);

// Normal stress n^T sigma n along each edge (current direction n, Cauchy stress sigma), in
// kTetEdges order: what the fracture pass compares with its threshold.
std::array<double, 6> edgeNormalStress(MaterialModel model, const Lame& lame, const TetRest& rest,
                                       const TetPoints& x, const EdgeDamage& damage);

}  // namespace galsculpt
