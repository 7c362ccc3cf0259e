// A damaged element's edge-strain form over a number type, in the manner of eigen_svd.h: one
// source for the scalar kernel (element_kernels.h's evaluateEdgeStrainElement: double on the CPU
// and the GPU) and the SIMD lanes (cracked_lanes_body.h), so that each lane rounds exactly as
// the scalar kernel does. The edges' strains and their stiffness K, the force of the edge forces
// tau and the 12x12 stiffness G^T H G plus the edges' own curvature. Which cracks open (the
// opening problem, element_kernels.h's crackedStrainState) is scalar code that every caller
// runs element by element. `Math` gives the number type's operations.
#pragma once

#include "solver/fem/eigen_svd.h"
#include "solver/fem/host_device.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

// The tables below are local constants of each function: device code cannot read a host array.
// kEnds: the edges as vertex pairs (kTetEdges); kEdgesAt, kSignAt: the three edges at each
// vertex and the sign of d eps_e / d x_vertex there.
#define GALSCULPT_EDGE_ENDS \
  constexpr int kEnds[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}
#define GALSCULPT_EDGES_AT                                                     \
  constexpr int kEdgesAt[4][3] = {{0, 1, 2}, {0, 3, 4}, {1, 3, 5}, {2, 4, 5}}; \
  constexpr double kSignAt[4][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {1, 1, 1}}

// The six edge vectors d_k and raw Green strains (|d|^2 - |D|^2) / (2 |D|^2).
template <typename Math, typename T>
GALSCULPT_HD void edgeGreenStrainsOf(const T restLengthSq[6], const T x[12], T d[6][3],
                                     T strain[6]) {
  GALSCULPT_EDGE_ENDS;
  for (int e = 0; e < 6; ++e) {
    const int a = kEnds[e][0], b = kEnds[e][1];
    T len2 = Math::all(0.0);
    for (int k = 0; k < 3; ++k) {
      d[e][k] = x[3 * b + k] - x[3 * a + k];
      len2 += d[e][k] * d[e][k];
    }
    strain[e] = (len2 - restLengthSq[e]) / (2.0 * restLengthSq[e]);
  }
}

// The strain-space stiffness K = B^-T C B^-1 on the six edge Green strains: the element's
// St. Venant-Kirchhoff energy is 1/2 eps^T K eps. Isotropic C on (E11,E22,E33,E12,E13,E23) is
// lambda t t^T + diag(2mu, 2mu, 2mu, 4mu, 4mu, 4mu) with t = (1,1,1,0,0,0) (shear entries count
// twice in E:E), so K = lambda a a^T + S^T W S with S = B^-1 (`s`, column-major: s[m + 6 c]) and
// a = S^T t: a quarter of the arithmetic of forming C B^-1 first, and exactly symmetric by
// construction.
template <typename T>
GALSCULPT_HD void edgeStrainStiffnessOf(const Lame& lame, const T* s, T k[6][6]) {
  T a[6];
  for (int c = 0; c < 6; ++c) a[c] = s[6 * c] + s[1 + 6 * c] + s[2 + 6 * c];
  const double normal = 2.0 * lame.mu, shear = 4.0 * lame.mu;
  for (int r = 0; r < 6; ++r) {
    const T* sr = s + 6 * r;
    for (int c = r; c < 6; ++c) {
      const T* sc = s + 6 * c;
      const T sum = normal * (sr[0] * sc[0] + sr[1] * sc[1] + sr[2] * sc[2]) +
                    shear * (sr[3] * sc[3] + sr[4] * sc[4] + sr[5] * sc[5]) +
                    lame.lambda * a[r] * a[c];
      k[r][c] = k[c][r] = sum;
    }
  }
}

// d eps_k / d x_b = d_k / |D_k|^2 = -d eps_k / d x_a for edge (a, b).
template <typename T>
GALSCULPT_HD void edgeStrainGradientsOf(const T d[6][3], const T restLengthSq[6], T g[6][3]) {
  for (int e = 0; e < 6; ++e)
    for (int c = 0; c < 3; ++c) g[e][c] = d[e][c] / restLengthSq[e];
}

// The corners' force of the edge forces tau: V tau_e g_e on each edge's second vertex, its
// opposite on the first (an edge without force adds nothing, not even a zero).
template <typename Math, typename T>
GALSCULPT_HD void edgeForceOf(const T& volume, const T tau[6], const T g[6][3], T gradient[12]) {
  GALSCULPT_EDGE_ENDS;
  for (int i = 0; i < 12; ++i) gradient[i] = Math::all(0.0);
  for (int e = 0; e < 6; ++e) {
    const auto loaded = tau[e] != 0.0;
    const int a = kEnds[e][0], b = kEnds[e][1];
    for (int c = 0; c < 3; ++c) {
      gradient[3 * b + c] = Math::select(loaded, gradient[3 * b + c] + volume * tau[e] * g[e][c],
                                         gradient[3 * b + c]);
      gradient[3 * a + c] = Math::select(loaded, gradient[3 * a + c] - volume * tau[e] * g[e][c],
                                         gradient[3 * a + c]);
    }
  }
}

// G^T H G (H: the edge forces' stiffness in the edge strains), the blocks on and above the
// diagonal: emit(a, c, sum) with sum[r][col] the entry (r, col) of block (a, c), c >= a. G's
// row for edge e is -g_e at its first vertex and +g_e at its second, so block (a, c) is
// sum over f at c of +-u_af g_f^T, with u_af = V sum over e at a of +-H_ef g_e: 486
// multiply-adds where the entry-by-entry sum over edge pairs took 1,296. (A sign of -1 adds
// -(u g), the same bits as subtracting u g.)
template <typename Math, typename T, typename Emit>
GALSCULPT_HD void edgeStrainBlocksOf(const T& volume, const T g[6][3], const T stiffness[6][6],
                                     Emit emit) {
  GALSCULPT_EDGES_AT;
  T u[4][6][3];
  for (int a = 0; a < 4; ++a)
    for (int f = 0; f < 6; ++f)
      for (int r = 0; r < 3; ++r) {
        T sum = Math::all(0.0);
        for (int i = 0; i < 3; ++i) {
          const int e = kEdgesAt[a][i];
          sum += kSignAt[a][i] * stiffness[e][f] * g[e][r];
        }
        u[a][f][r] = volume * sum;
      }
  for (int a = 0; a < 4; ++a)
    for (int c = a; c < 4; ++c) {
      T sum[3][3];
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) sum[r][col] = Math::all(0.0);
      for (int i = 0; i < 3; ++i) {
        const int f = kEdgesAt[c][i];
        for (int r = 0; r < 3; ++r)
          for (int col = 0; col < 3; ++col) {
            const T term = u[a][f][r] * g[f][col];
            sum[r][col] = kSignAt[c][i] > 0.0 ? sum[r][col] + term : sum[r][col] - term;
          }
      }
      emit(a, c, sum);
    }
}

// The second derivative of eps_k is [I -I; -I I] / |D_k|^2: each edge's own curvature block
// V tau_e / |D_e|^2, indefinite only for a compressive edge force, which projection drops.
// add(a, b, block, pulls) for edge (a, b): `pulls`, the lanes where the block is not zero.
template <typename Math, typename T, typename Add>
GALSCULPT_HD void edgeCurvatureOf(const T& volume, const T tau[6], const T restLengthSq[6],
                                  bool project, Add add) {
  GALSCULPT_EDGE_ENDS;
  for (int e = 0; e < 6; ++e) {
    T t = tau[e] / restLengthSq[e];
    if (project) t = Math::select(t > 0.0, t, Math::all(0.0));
    const auto pulls = t != 0.0;
    if (!Math::any(pulls)) continue;
    add(kEnds[e][0], kEnds[e][1], volume * t, pulls);
  }
}

}  // namespace galsculpt::kernels

#undef GALSCULPT_EDGE_ENDS
#undef GALSCULPT_EDGES_AT
