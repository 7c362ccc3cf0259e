// The smooth crack-closure law: how a damaged edge's crack faces meet (docs/physics.md, "A crack
// that closes smoothly"). The hard law lets the faces touch and then resists with the whole
// elastic stiffness at once, so a crack's stiffness jumps from none to all at contact and
// Newton's steps overshoot the faces. The smooth law lets two faces that touch press into each
// other by at most `width` (a strain), through a barrier on the opening c of each closing edge:
//
//   g(c) = kappa w^2 h(-c / w),  h(s) = s^3 / (3 (1 - s)) for 0 <= s < 1,  0 for s <= 0,
//
// with kappa the edge's own stiffness K_ee. h is convex, h(0) = h'(0) = h''(0) = 0 and h grows
// without bound as s -> 1: the faces feel nothing while apart or just touching (no force at
// rest, no drift), stiffen smoothly as they press, and never pass each other by more than w.
// The element's energy min_c 1/2 (eps - c)^T K (eps - c) + sum g(c_e) is then C2 and convex in
// the strains; as w -> 0 it is the hard law.
//
// Here too: a damaged element's state in strain space (CrackedStrainState), which
// element_kernels.h's crackedStrainState fills, and the smooth law's part of it.
//
// Header only, no allocation: __host__ __device__ under nvcc, like element_kernels.h.
#pragma once

#include <cmath>
#include <cstdint>

#include "solver/fem/kernel_math.h"

namespace galsculpt::kernels {

// h, h' and h'' at s = -c / w, the barrier's shape (zero for s <= 0).
struct CrackBarrier {
  double value = 0.0, slope = 0.0, curvature = 0.0;
};

GALSCULPT_HD CrackBarrier crackBarrierShape(double s) {
  CrackBarrier b;
  if (!(s > 0.0)) return b;
  const double open = 1.0 - s;
  b.value = s * s * s / (3.0 * open);
  b.slope = s * s * (3.0 - 2.0 * s) / (3.0 * open * open);
  b.curvature = 2.0 * s * (3.0 - 3.0 * s + s * s) / (3.0 * open * open * open);
  return b;
}

// g(c), g'(c) and g''(c) of one closing edge with stiffness kappa and width w.
GALSCULPT_HD CrackBarrier crackBarrier(double c, double kappa, double width) {
  const CrackBarrier h = crackBarrierShape(-c / width);
  CrackBarrier g;
  g.value = kappa * width * width * h.value;
  g.slope = -kappa * width * h.slope;
  g.curvature = kappa * h.curvature;
  return g;
}

// The edges of `mask` in order (index[0..n)); n.
GALSCULPT_HD int edgesOf(std::uint8_t mask, int index[6]) {
  int n = 0;
  for (int e = 0; e < 6; ++e)
    if ((mask >> e) & 1) index[n++] = e;
  return n;
}

// K_UU + diag(curvature_U), column-major n x n, U = index[0..n) (curvature indexed by edge): the
// opening problem's Newton matrix and, at the solution, the matrix its Schur complement inverts.
GALSCULPT_HD void openingMatrix(const double k[6][6], const int index[6], int n,
                                const double curvature[6], double m[36]) {
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) m[i + n * j] = k[index[i]][index[j]];
    m[i + n * i] += curvature[index[i]];
  }
}

// The openings c that minimize 1/2 (eps - c)^T K (eps - c) + sum over oneWay edges of g(c_e),
// with c_e free on `free` edges and 0 on the others, by Newton's method from `c` (the hard law's
// openings: a start on the right side of every barrier). The problem is strictly convex (K is
// positive definite, g convex), so Newton with a backtracking on the objective and steps kept
// inside the barriers converges, quadratically near the end. `c` returns the openings.
GALSCULPT_HD void smoothCrackOpenings(const double k[6][6], const double eps[6], std::uint8_t free,
                                      std::uint8_t oneWay, double width, double c[6]) {
  int index[6];
  const int n = edgesOf(free | oneWay, index);
  if (n == 0) return;
  double scale = width;
  for (int e = 0; e < 6; ++e) scale = fabs(eps[e]) > scale ? fabs(eps[e]) : scale;
  auto objective = [&](const double* at) {
    double r[6], value = 0.0;
    for (int a = 0; a < 6; ++a) r[a] = eps[a] - at[a];
    for (int a = 0; a < 6; ++a) {
      double row = 0.0;
      for (int b = 0; b < 6; ++b) row += k[a][b] * r[b];
      value += 0.5 * r[a] * row;
      if ((oneWay >> a) & 1) value += crackBarrier(at[a], k[a][a], width).value;
    }
    return value;
  };
  double current = objective(c);
  for (int iteration = 0; iteration < 60; ++iteration) {
    double m[36], step[6], curvature[6] = {};
    for (int i = 0; i < n; ++i) {
      const int e = index[i];
      double force = 0.0;  // (K (eps - c))_e
      for (int b = 0; b < 6; ++b) force += k[e][b] * (eps[b] - c[b]);
      double slope = 0.0;
      if ((oneWay >> e) & 1) {
        const CrackBarrier g = crackBarrier(c[e], k[e][e], width);
        slope = g.slope;
        curvature[e] = g.curvature;
      }
      step[i] = force - slope;  // minus the objective's gradient in c_e
    }
    openingMatrix(k, index, n, curvature, m);
    if (!cholesky(n, m)) return;
    choleskySolve(n, m, step);
    // Inside every barrier: at most 9/10 of the way to it.
    double alpha = 1.0;
    for (int i = 0; i < n; ++i) {
      const int e = index[i];
      if (!((oneWay >> e) & 1) || !(step[i] < 0.0)) continue;
      const double room = c[e] + width;
      if (alpha * -step[i] > 0.9 * room) alpha = 0.9 * room / -step[i];
    }
    double trial[6], value = current, largest = 0.0;
    for (int tries = 0; tries < 40; ++tries) {
      for (int a = 0; a < 6; ++a) trial[a] = c[a];
      for (int i = 0; i < n; ++i) trial[index[i]] = c[index[i]] + alpha * step[i];
      value = objective(trial);
      // Near the minimum a Newton step changes the objective by less than its round-off: such
      // a step is taken (its accuracy is in the step, not in the objective's last bits).
      if (value <= current + 1e-13 * fabs(current)) break;
      alpha *= 0.5;
    }
    if (!(value <= current + 1e-13 * fabs(current))) return;  // no descent left
    for (int i = 0; i < n; ++i) {
      largest = fabs(alpha * step[i]) > largest ? fabs(alpha * step[i]) : largest;
      c[index[i]] = trial[index[i]];
    }
    current = value;
    if (largest <= 1e-13 * scale) return;
  }
}

// The strain-space state of a damaged element: the edge forces tau = dPsi/d eps (eps the six
// raw edge Green strains), the elastic edge strains z (what the material is strained by once the
// cracks have opened: the stress is C B^-1 z), the energy, and d2Psi/d eps2.
struct CrackedStrainState {
  double tau[6];
  double z[6];
  double energy;
  double stiffness[6][6];
  bool unloaded;        // every crack open: all of the above is zero
  std::uint8_t opened;  // the damaged edges whose cracks are open (the active set)
};

// The smooth law's energy, forces and stiffness at its openings, found from the hard law's
// openings `c` (smoothCrackOpenings; `c` returns them).
GALSCULPT_HD void addSmoothCrackEnergy(const double k[6][6], const double eps[6], std::uint8_t free,
                                       std::uint8_t oneWay, double width, double c[6],
                                       bool wantStiffness, CrackedStrainState& out) {
  smoothCrackOpenings(k, eps, free, oneWay, width, c);
  const std::uint8_t unknown = free | oneWay;
  std::uint8_t opened = free;
  double slope[6] = {}, curvature[6] = {};
  for (int e = 0; e < 6; ++e) {
    if (!((oneWay >> e) & 1)) continue;
    if (c[e] >= 0.0) opened |= static_cast<std::uint8_t>(1u << e);
    const CrackBarrier g = crackBarrier(c[e], k[e][e], width);
    slope[e] = g.slope;
    curvature[e] = g.curvature;
    out.energy += g.value;
  }
  out.opened = opened;
  double r[6];
  for (int e = 0; e < 6; ++e) r[e] = eps[e] - c[e];
  for (int a = 0; a < 6; ++a) {
    double force = 0.0;
    for (int b = 0; b < 6; ++b) force += k[a][b] * r[b];
    out.energy += 0.5 * r[a] * force;
    out.tau[a] += ((unknown >> a) & 1) ? slope[a] : force;
    out.z[a] += r[a];
  }
  if (!wantStiffness) return;
  // d2 Psi / d eps2 = K - K_:U (K_UU + G'')^-1 K_U: (U the damaged edges).
  int index[6];
  const int n = edgesOf(unknown, index);
  double m[36], x[6][6];
  openingMatrix(k, index, n, curvature, m);
  if (!cholesky(n, m)) return;  // only with a NaN strain: the forces carry it
  for (int col = 0; col < 6; ++col) {
    double rhs[6];
    for (int i = 0; i < n; ++i) rhs[i] = k[index[i]][col];
    choleskySolve(n, m, rhs);
    for (int i = 0; i < n; ++i) x[i][col] = rhs[i];
  }
  for (int a = 0; a < 6; ++a) {
    const bool openRow = (opened >> a) & 1;
    for (int b = a; b < 6; ++b) {
      double v = k[a][b];
      for (int i = 0; i < n; ++i) v -= k[a][index[i]] * x[i][b];
      if (openRow || ((opened >> b) & 1)) v = 0.0;
      out.stiffness[a][b] += v;
      if (b != a) out.stiffness[b][a] += v;
    }
  }
}

}  // namespace galsculpt::kernels
