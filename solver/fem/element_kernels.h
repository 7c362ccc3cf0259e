// One tetrahedron's physics in plain arrays, compiled for both the CPU and the GPU, for every
// material model alike: rest data, deformation gradient, the eigensystem of dP/dF, the damaged
// elements' edge-strain form (cracks that open one way) and the plastic return of plasticity.h.
// What evaluates a material model (the element's energy, force and stiffness, the edge normal
// stresses of the fracture pass) is material_kernels.h, apart so that an edit of a model
// recompiles only the translation units that evaluate one. The CPU solver calls these same
// functions (through tet_element.cpp and plasticity.cpp), so the CUDA backend runs exactly the
// element code the CPU tests check.
//
// Header only, no Eigen, no exceptions, no allocation: every function is __host__ __device__
// under nvcc. Matrices are column-major arrays (a[r + 3 c]), as Eigen stores them, so the CPU
// side converts by copying. The 3x3 SVD and symmetric eigen-solves are cyclic Jacobi: robust
// for repeated and zero singular values, with no fallback path to keep in step on the device.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "solver/fem/crack_law.h"
#include "solver/fem/edge_strain_element.h"
#include "solver/fem/hencky_strain.h"
#include "solver/fem/intact_element.h"
#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt {

// The six edges of a tet as vertex pairs: the order of edge masks, edge stresses and each tet's
// edge indices (SimModel::tetEdges) everywhere.
inline constexpr int kTetEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

}  // namespace galsculpt

namespace galsculpt::kernels {

// kTetEdges in device code (which cannot read a host array): vertex `end` (0, 1) of `edge`.
GALSCULPT_HD constexpr int edgeVertex(int edge, int end) {
  return end == 0 ? (edge < 3   ? 0
                     : edge < 5 ? 1
                                : 2)
                  : (edge < 3   ? edge + 1
                     : edge < 5 ? edge - 1
                                : 3);
}
static_assert(edgeVertex(0, 0) == kTetEdges[0][0] && edgeVertex(0, 1) == kTetEdges[0][1] &&
                  edgeVertex(1, 1) == kTetEdges[1][1] && edgeVertex(2, 1) == kTetEdges[2][1] &&
                  edgeVertex(3, 0) == kTetEdges[3][0] && edgeVertex(3, 1) == kTetEdges[3][1] &&
                  edgeVertex(4, 0) == kTetEdges[4][0] && edgeVertex(4, 1) == kTetEdges[4][1] &&
                  edgeVertex(5, 0) == kTetEdges[5][0] && edgeVertex(5, 1) == kTetEdges[5][1],
              "edgeVertex is kTetEdges");
constexpr std::uint8_t kIntact = 0x3f;

enum class Hessian { None, Exact, ProjectedSpd };

// Rest data of one element (what tet_element.h's TetRest holds).
struct RestData {
  double dmInverse[9];         // column-major inverse of [X1-X0, X2-X0, X3-X0]
  double volume;               // m^3
  double restLengthSq[6];      // |D_k|^2
  double strainFromEdges[36];  // column-major B^-1: (E11,E22,E33,E12,E13,E23) from edge strains
};

// --- materials in singular values (material_kernels.h evaluates them) ----------------------

using SingularValueEnergy = SingularValueEnergyOf<double, M3>;

// --- intact elements (intact_element.h's, for double) ----------------------------------------

GALSCULPT_HD M3 dmInverseOf(const RestData& rest) {
  M3 dmInv;
  for (int i = 0; i < 9; ++i) dmInv.a[i] = rest.dmInverse[i];
  return dmInv;
}

GALSCULPT_HD M3 deformationGradient(const RestData& rest, const double x[12]) {
  return deformationGradientOf(dmInverseOf(rest), x);
}

// Shape-function gradients: F = sum_a x_a c_a^T, c_0 = -(c_1 + c_2 + c_3); c[a][j].
GALSCULPT_HD void shapeGradients(const RestData& rest, double c[4][3]) {
  shapeGradientsOf<ScalarMath>(dmInverseOf(rest), c);
}

// The analytic eigensystem of dP/dF (intact_element.h): visit(lambda, Q) for its 3 scaling, 3
// twist and 3 flip modes.
template <typename Visit>
GALSCULPT_HD void forEachStressMode(const M3& u, const double s[3], const M3& v,
                                    const SingularValueEnergy& e, Visit visit) {
  forEachStressModeOf<ScalarMath>(u, s, v, e, true, visit);
}

// dP/dF (9x9, column-major vec(F)), exact or projected to SPD.
GALSCULPT_HD void eigenSystemHessian(const M3& u, const double s[3], const M3& v,
                                     const SingularValueEnergy& e, bool projectSpd, double h[81]) {
  for (int i = 0; i < 81; ++i) h[i] = 0.0;
  forEachStressMode(u, s, v, e, [&](double lambda, const M3& mode) {
    if (projectSpd) lambda = fmax(lambda, 0.0);
    if (lambda == 0.0) return;
    for (int c = 0; c < 9; ++c)
      for (int r = 0; r < 9; ++r) h[r + 9 * c] += lambda * mode.a[r] * mode.a[c];
  });
}

// --- damaged elements: St. Venant-Kirchhoff in the edge strains, cracks open one way ---------

// The strain-space stiffness K on the six edge Green strains (edge_strain_element.h): the
// element's St. Venant-Kirchhoff energy is 1/2 eps^T K eps.
GALSCULPT_HD void edgeStrainStiffness(const Lame& lame, const RestData& rest, double k[6][6]) {
  edgeStrainStiffnessOf(lame, rest.strainFromEdges, k);
}

// Eliminates the edges in `set` from [K | rhs] (the LDL^T of K on the set: symmetric pivots,
// upper triangle only). Leaves in h and b, on the rows and columns off the set, the Schur
// complement and rhs - K c, and in c the solution of K_ss c_s = rhs_s (by back substitution
// through the pivots' rows; zero off the set). For the opening problem (rhs = K eps): the closed
// edges' forces (K (eps - c))_c, their stiffness H (tau = H eps) and the openings, from one
// elimination where a Cholesky solve and a separate elimination took twice the arithmetic.
// `Set`: the set as a byte, or as a std::integral_constant (eliminateEdges below).
template <typename Set>
GALSCULPT_HD void eliminateEdgesIn(Set set, const double k[6][6], const double rhs[6],
                                   double h[6][6], double b[6], double c[6]) {
  GALSCULPT_UNROLL
  for (int r = 0; r < 6; ++r) {
    b[r] = rhs[r];
    c[r] = 0.0;
    GALSCULPT_UNROLL
    for (int m = r; m < 6; ++m) h[r][m] = k[r][m];
  }
  unsigned alive = kIntact;  // the rows and columns not yet eliminated
  GALSCULPT_UNROLL
  for (int o = 0; o < 6; ++o) {
    if (!((set >> o) & 1)) continue;
    alive &= ~(1u << o);
    const double inverse = 1.0 / h[o][o];  // K is positive definite: so is every pivot
    GALSCULPT_UNROLL
    for (int r = 0; r < 6; ++r) {
      if (!((alive >> r) & 1)) continue;
      const double factor = (r < o ? h[r][o] : h[o][r]) * inverse;
      GALSCULPT_UNROLL
      for (int m = r; m < 6; ++m)
        if ((alive >> m) & 1) h[r][m] -= factor * (m < o ? h[m][o] : h[o][m]);
      b[r] -= factor * b[o];
    }
  }
  GALSCULPT_UNROLL
  for (int o = 5; o >= 0; --o) {
    if (!((set >> o) & 1)) continue;
    double sum = b[o];
    GALSCULPT_UNROLL
    for (int m = o + 1; m < 6; ++m)
      if ((set >> m) & 1) sum -= h[o][m] * c[m];
    c[o] = sum / h[o][o];
  }
}

#if !defined(__CUDA_ARCH__)
// On the CPU each of the 64 sets has its own copy of the elimination, its loops unrolled and
// its tests of the set decided at compile time: the same operations in the same order (the same
// bits), without the branches on the set's bits that mispredicted from one element to the next
// (the elimination was about half of a damaged element's evaluation without stiffness).
using EliminateEdgesFn = void (*)(const double (*)[6], const double*, double (*)[6], double*,
                                  double*);
template <unsigned S>
void eliminateEdgesOfSet(const double k[6][6], const double rhs[6], double h[6][6], double b[6],
                         double c[6]) {
  eliminateEdgesIn(std::integral_constant<unsigned, S>{}, k, rhs, h, b, c);
}
template <unsigned... S>
constexpr std::array<EliminateEdgesFn, sizeof...(S)> eliminateEdgesTable(
    std::integer_sequence<unsigned, S...>) {
  return {&eliminateEdgesOfSet<S>...};
}
inline constexpr std::array<EliminateEdgesFn, 64> kEliminateEdges =
    eliminateEdgesTable(std::make_integer_sequence<unsigned, 64>{});
#endif

GALSCULPT_HD void eliminateEdges(const double k[6][6], const double rhs[6], std::uint8_t set,
                                 double h[6][6], double b[6], double c[6]) {
#if defined(__CUDA_ARCH__)
  eliminateEdgesIn(set, k, rhs, h, b, c);
#else
  kEliminateEdges[set & kIntact](k, rhs, h, b, c);
#endif
}

// How far a one-way crack's edge strain may fall below zero before the crack closes: far above
// the round-off of an edge's Green strain (a few 1e-16 relative to the body's size over the
// edge's, and growing with the frames that two executors' different roundings put between their
// positions), far below any compression a load makes. A crack the knife leaves is at zero strain,
// a tie between open and closed, for thousands of edges at once; decided by the sign of the
// round-off, each executor and each perturbation of the start closes another set, and the
// damping's stiffness, frozen at the frame's start, differs between them (a split sphere's tight
// solutions 25 % of its motion apart). With the threshold a crack at rest is open on every one.
inline constexpr double kCrackClosingStrain = 5e-11;

// Adds to `out` the energy min over openings c of 1/2 (eps - c)^T K (eps - c), with c_e free on
// the edges in `free`, c_e >= -kCrackClosingStrain on those in `oneWay` and 0 elsewhere (the
// one-way edges' strains shifted by the threshold, c_e >= 0: the same problem). It is convex and C1
// in eps (a partial minimum of a convex quadratic over a convex set); its gradient tau = K (eps -
// c*) is zero on every opened edge and compressive (<= 0) on every closed one-way edge, and its
// Hessian is the Schur complement of K on the opened edges. The openings solve a linear
// complementarity problem with a positive definite matrix: Murty's least-index principal
// pivoting finds the opened set exactly in finitely many flips (at most 2^6 sets), starting from
// the edges that are not compressed. A crack at rest (zero strain, zero force) is a tie between
// open and closed; it counts as open, so that a freshly cut body's linearized step lets its
// sides part (counted closed, its stiffness would glue them for that step).
GALSCULPT_HD void addOpenedCrackEnergy(const double k[6][6], const double raw[6], std::uint8_t free,
                                       std::uint8_t oneWay, double width, bool wantStiffness,
                                       CrackedStrainState& out) {
  double eps[6];
  for (int e = 0; e < 6; ++e) eps[e] = ((oneWay >> e) & 1) ? raw[e] + kCrackClosingStrain : raw[e];
  // K is positive definite: its largest entry is on its diagonal. (Comparisons, not fmax: a
  // library call per entry on the CPU, a sixth of this function's time.)
  double keps[6], scale = 0.0, kScale = 0.0;
  for (int r = 0; r < 6; ++r) {
    keps[r] = 0.0;
    for (int c = 0; c < 6; ++c) keps[r] += k[r][c] * eps[c];
    kScale = k[r][r] > kScale ? k[r][r] : kScale;
    scale = fabs(eps[r]) > scale ? fabs(eps[r]) : scale;
  }
  std::uint8_t opened = free;
  for (int e = 0; e < 6; ++e)
    if (((oneWay >> e) & 1) && eps[e] >= 0.0) opened |= static_cast<std::uint8_t>(1u << e);
  double h[6][6], b[6], c[6];
  const double tolerance = 1e-13 * scale;
  for (int flip = 0; flip <= 64; ++flip) {
    eliminateEdges(k, keps, opened, h, b, c);
    int violated = -1;
    for (int e = 0; e < 6 && violated < 0; ++e) {
      if (!((oneWay >> e) & 1)) continue;
      const bool open = (opened >> e) & 1;
      if ((open && c[e] < -tolerance) || (!open && b[e] > tolerance * kScale)) violated = e;
    }
    if (violated < 0) break;
    opened ^= static_cast<std::uint8_t>(1u << violated);
  }
  if (width > 0.0 && (oneWay & ~opened)) {
    addSmoothCrackEnergy(k, eps, free, oneWay, width, c, wantStiffness, out);
    return;
  }
  // H on the closed edges only: the opened edges' strains enter nothing, exactly (a vertex whose
  // edges all opened moves no other force, bit for bit).
  for (int r = 0; r < 6; ++r) {
    const bool openRow = (opened >> r) & 1;
    for (int m = r; m < 6; ++m) {
      const double v = openRow || ((opened >> m) & 1) ? 0.0 : h[r][m];
      h[r][m] = h[m][r] = v;
    }
  }
  out.opened = opened;
  for (int r = 0; r < 6; ++r) {
    double t = 0.0;
    for (int m = 0; m < 6; ++m) t += h[r][m] * eps[m];
    out.tau[r] += t;
    out.z[r] += eps[r] - c[r];
    out.energy += 0.5 * eps[r] * t;
  }
  if (!wantStiffness) return;
  for (int r = 0; r < 6; ++r)
    for (int m = 0; m < 6; ++m) out.stiffness[r][m] += h[r][m];
}

// Whether an element's intact edges are exactly two opposite ones (0-1 with 2-3, 0-2 with 1-3,
// 0-3 with 1-2): it holds two pieces, each intact edge a bar of its own (crackedStrainState).
GALSCULPT_HD constexpr bool holdsTwoPieces(std::uint8_t intact) {
  return intact == 0x21 || intact == 0x12 || intact == 0x0c;
}

// A damaged element in strain space. Damaged edges carry no tension: their cracks open freely
// (the opening absorbs all of the edge's stretch, so not even the coupling through the other
// edges pulls on it) and, where damaged edges resist compression, close against each other.
// With only two opposite edges intact the element holds two pieces (say {0, 1} and {2, 3}):
// each intact edge is then a bar of its own with the uniaxial stiffness 1 / (K^-1)_ee, and the
// closing contact acts on the four edges between them, so neither piece feels the other move
// unless they touch.
GALSCULPT_HD void crackedStrainState(const Lame& lame, const RestData& rest, const double eps[6],
                                     std::uint8_t intact, bool compressionResists,
                                     bool wantStiffness, CrackedStrainState& out) {
  out.energy = 0.0;
  for (int r = 0; r < 6; ++r) {
    out.tau[r] = out.z[r] = 0.0;
    for (int c = 0; c < 6; ++c) out.stiffness[r][c] = 0.0;
  }
  const std::uint8_t damaged = static_cast<std::uint8_t>(~intact & kIntact);
  const std::uint8_t oneWay = compressionResists ? damaged : 0;
  // Every edge damaged and no crack closed (pressed shorter than at rest, past the threshold):
  // all six open, the
  // element carries nothing, exactly. The common case in a body cut to pieces (after 100
  // random cuts through the sphere, a quarter of the damaged elements' evaluations), spared
  // its stiffness and the elimination that would return zeros up to round-off.
  out.unloaded = intact == 0;
  for (int e = 0; e < 6 && out.unloaded; ++e)
    out.unloaded = !((oneWay >> e) & 1) || eps[e] + kCrackClosingStrain >= 0.0;
  out.opened = out.unloaded ? damaged : static_cast<std::uint8_t>(damaged & ~oneWay);
  if (out.unloaded) return;
  double k[6][6];
  edgeStrainStiffness(lame, rest, k);
  if (!holdsTwoPieces(intact)) {
    addOpenedCrackEnergy(k, eps, static_cast<std::uint8_t>(damaged & ~oneWay), oneWay,
                         lame.crackWidth, wantStiffness, out);
    return;
  }
  for (int e = 0; e < 6; ++e) {
    if (!((intact >> e) & 1)) continue;
    // Eliminating the other five edges from K's column e: their strains w (as a multiple of
    // eps_e) when only edge e is held, and in h[e][e] the bar's stiffness 1 / (K^-1)_ee.
    const double column[6] = {k[0][e], k[1][e], k[2][e], k[3][e], k[4][e], k[5][e]};
    double h[6][6], b[6], w[6];
    eliminateEdges(k, column, static_cast<std::uint8_t>(kIntact & ~(1u << e)), h, b, w);
    const double bar = h[e][e];
    out.tau[e] += bar * eps[e];
    out.energy += 0.5 * bar * eps[e] * eps[e];
    out.stiffness[e][e] += bar;
    for (int r = 0; r < 6; ++r) out.z[r] += eps[e] * (r == e ? 1.0 : -w[r]);
  }
  // The intact edges enter the opening problem as free (each bar is accounted above), so the
  // set it reports carries them too: the damaged edges' cracks are what `opened` names.
  if (oneWay) addOpenedCrackEnergy(k, eps, intact, oneWay, lame.crackWidth, wantStiffness, out);
  out.opened &= damaged;
}

// The six edge vectors d_k and raw Green strains (|d|^2 - |D|^2) / (2 |D|^2).
GALSCULPT_HD void edgeGreenStrains(const RestData& rest, const double x[12], double d[6][3],
                                   double strain[6]) {
  edgeGreenStrainsOf<ScalarMath>(rest.restLengthSq, x, d, strain);
}

// Writes the 12x12 Hessian of the edge-strain energy: G^T H G plus the edges' own curvature
// (edge_strain_element.h; g: the strains' gradients d_e / |D_e|^2, which the caller has for the
// force), the lower blocks the upper ones' transposes.
GALSCULPT_HD void edgeStrainHessian(const RestData& rest, const double g[6][3],
                                    const CrackedStrainState& state, Hessian mode,
                                    double* hessian) {
  // Each block and its mirror, entry by entry (a diagonal block's entry below its diagonal
  // ends as the sum at its upper-triangle position).
  edgeStrainBlocksOf<ScalarMath>(rest.volume, g, state.stiffness,
                                 [&](int a, int c, const double sum[3][3]) {
                                   for (int col = 0; col < 3; ++col)
                                     for (int r = 0; r < 3; ++r) {
                                       hessian[(3 * a + r) + 12 * (3 * c + col)] = sum[r][col];
                                       hessian[(3 * c + col) + 12 * (3 * a + r)] = sum[r][col];
                                     }
                                 });
  edgeCurvatureOf<ScalarMath>(rest.volume, state.tau, rest.restLengthSq,
                              mode == Hessian::ProjectedSpd, [&](int a, int b, double block, bool) {
                                for (int c = 0; c < 3; ++c) {
                                  hessian[(3 * a + c) + 12 * (3 * a + c)] += block;
                                  hessian[(3 * b + c) + 12 * (3 * b + c)] += block;
                                  hessian[(3 * a + c) + 12 * (3 * b + c)] -= block;
                                  hessian[(3 * b + c) + 12 * (3 * a + c)] -= block;
                                }
                              });
}

// `hessian` (12x12 column-major) may be null when mode is None; `opened`, when not null, gets
// the damaged edges whose cracks are open (CrackedStrainState::opened).
GALSCULPT_HD void evaluateEdgeStrainElement(const Lame& lame, const RestData& rest,
                                            const double x[12], std::uint8_t intact,
                                            bool compressionResists, Hessian mode, double& energy,
                                            double gradient[12], double* hessian,
                                            std::uint8_t* opened = nullptr) {
  double d[6][3], strain[6];
  edgeGreenStrains(rest, x, d, strain);
  CrackedStrainState state;
  crackedStrainState(lame, rest, strain, intact, compressionResists, mode != Hessian::None, state);
  if (opened) *opened = state.opened;
  if (state.unloaded) {
    energy = 0.0;
    for (int i = 0; i < 12; ++i) gradient[i] = 0.0;
    if (mode != Hessian::None)
      for (int i = 0; i < 144; ++i) hessian[i] = 0.0;
    return;
  }
  energy = rest.volume * state.energy;
  double g[6][3];
  edgeStrainGradientsOf(d, rest.restLengthSq, g);
  edgeForceOf<ScalarMath>(rest.volume, state.tau, g, gradient);
  if (mode != Hessian::None) edgeStrainHessian(rest, g, state, mode, hessian);
}

// --- rest data and plasticity -----------------------------------------------------------------

// Rest data of the tet with corners p (12 coordinates); false for a degenerate tet.
GALSCULPT_HD bool computeRest(const double p[12], RestData& r) {
  M3 dm{};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) dm(k, c) = p[3 * (c + 1) + k] - p[k];
  const double det = determinant(dm);
  if (!(fabs(det) > 0.0)) return false;
  const M3 inv = inverse(dm);
  for (int i = 0; i < 9; ++i) r.dmInverse[i] = inv.a[i];
  r.volume = fabs(det) / 6.0;
  double b[36];
  for (int e = 0; e < 6; ++e) {
    double n[3], len2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      n[k] = p[3 * edgeVertex(e, 1) + k] - p[3 * edgeVertex(e, 0) + k];
      len2 += n[k] * n[k];
    }
    r.restLengthSq[e] = len2;
    const double len = sqrt(len2);
    for (double& v : n) v /= len;
    const double row[6] = {n[0] * n[0],     n[1] * n[1],     n[2] * n[2],
                           2 * n[0] * n[1], 2 * n[0] * n[2], 2 * n[1] * n[2]};
    for (int c = 0; c < 6; ++c) b[e + 6 * c] = row[c];
  }
  return invert6(b, r.strainFromEdges);
}

// The rest data of an element whose rest shape Fp Dm was deformed plastically (isochoric: the
// energy keeps its rest volume). False when the plastic shape is degenerate.
GALSCULPT_HD bool plasticRest(const RestData& rest, const M3& fpInverse, RestData& out) {
  M3 dmInv;
  for (int i = 0; i < 9; ++i) dmInv.a[i] = rest.dmInverse[i];
  const M3 plasticDm = multiply(inverse(fpInverse), inverse(dmInv));
  double p[12] = {0.0, 0.0, 0.0};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) p[3 * (c + 1) + k] = plasticDm(k, c);
  if (!computeRest(p, out)) return false;
  out.volume = rest.volume;
  return true;
}

struct PlasticParamsData {
  double yieldStress = 0.0;  // Pa (von Mises); 0 disables plasticity
  double hardening = 0.0;    // Pa
  // Whether a collapsed or inverted elastic part flows (by the continued logarithm): where the
  // model's energy includes the flow (MaterialInfo::flowInEnergy), the commit must flow as the
  // energy did. Another model's flow after the step leaves such an element alone: its energy
  // does not measure Hencky strain, and flowing a crushed element by it reshapes its rest shape
  // without bound.
  bool flowsCollapsed = false;
};

// The closed-form test's margin: its eigenvalues' round-off (about 1e-8 of the strain) is far
// below a tenth of any yield strain, so an element it passes would not flow by the SVD either.
constexpr double kClearlyElasticMargin = 0.9;

// Commits a step's flow: the radial return of F Fp^-1 onto the von Mises yield surface in its
// Hencky strains (hencky_strain.h), the same flow the Hencky model's energy minimized over in
// the step (so a converged step is in equilibrium after it). Updates fpInverse and the
// accumulated plastic strain; true when the element flowed. The flow is isochoric and coaxial:
// with F Fp^-1 = U diag(s) V^T and dEp the plastic part of the deviator, Fp^-1 becomes
// Fp^-1 V diag(exp(-dEp)) V^T, so the elastic part's stretches are s exp(-dEp).
GALSCULPT_HD bool plasticReturn(const Lame& lame, const PlasticParamsData& params, const M3& f,
                                M3& fpInverse, double& plasticStrain) {
  if (params.yieldStress <= 0.0) return false;
  const M3 fe = multiply(f, fpInverse);
  const double yield = params.yieldStress + params.hardening * plasticStrain;
  if (clearlyElastic(fe, lame.mu, yield, kClearlyElasticMargin)) return false;
  M3 u, v;
  double sigma[3];
  rotationVariantSvd(fe, u, sigma, v);
  if (!params.flowsCollapsed && fmin(sigma[0], fmin(sigma[1], sigma[2])) <= 1e-6) return false;
  const HenckyStrain h = henckyStrain(sigma);
  const DeviatoricFlow g = deviatoricFlow(lame.mu, yield, params.hardening, h.deviatorNorm);
  if (!(g.plasticStrain > 0.0)) return false;
  plasticStrain += g.plasticStrain;
  double stretch[3];
  for (int i = 0; i < 3; ++i) stretch[i] = exp(-(1.0 - g.keptFraction) * h.deviator[i]);
  fpInverse = multiply(fpInverse, scaledProduct(v, stretch, v));
  const double det = determinant(fpInverse);  // 1 but for round-off
  if (det > 0.0) {
    const double scale = 1.0 / cbrt(det);
    for (double& a : fpInverse.a) a *= scale;
  }
  return true;
}

}  // namespace galsculpt::kernels
