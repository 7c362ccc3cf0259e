// Hencky (logarithmic) principal strains and von Mises flow in them (docs/physics.md,
// "Plasticity inside the solve"). Two users share these functions so that they agree bit for
// bit: the Hencky model's energy (materials/hencky.h), where the flow of a step is part of what
// each Newton iteration minimizes, and the return map that commits that flow once the step has
// converged (element_kernels.h's plasticReturn). Model-neutral: no material file is included.
#pragma once

#include <cmath>

#include "solver/fem/kernel_math.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

// Below this stretch the logarithm is continued by its second-order Taylor polynomial, so that
// the strain, its slope and its curvature stay finite for a crushed or inverted element (a
// negative singular value) and still push it back: the extension keeps growing in magnitude.
constexpr double kLogStretchFloor = 0.1;

// `base` for an element whose accumulated plastic strain is `plasticStrain`: its yield stress
// raised by the hardening (where the model's energy includes the flow, base.yield > 0).
GALSCULPT_HD Lame hardenedLame(Lame base, double plasticStrain) {
  if (base.yield > 0.0) base.yield += base.hardening * plasticStrain;
  return base;
}

struct ExtendedLog {
  double value;      // l(s): log s above the floor
  double slope;      // l'(s) > 0
  double curvature;  // l''(s)
};

GALSCULPT_HD ExtendedLog extendedLog(double s) {
  constexpr double m = kLogStretchFloor;
  if (s >= m) return {log(s), 1.0 / s, -1.0 / (s * s)};
  const double t = s - m;
  return {log(m) + t / m - 0.5 * t * t / (m * m), 1.0 / m - t / (m * m), -1.0 / (m * m)};
}

// The deviatoric energy of the Hencky strain as a function of its deviator's norm s, with the
// step's flow minimized out (a variational constitutive update, Ortiz and Stainier 1999):
//   G(s) = min over dg >= 0 of  mu (s - sqrt(3/2) dg)^2 + yield dg + hardening/2 dg^2,
// yield the element's von Mises yield stress at the step's start (Pa; 0: elastic). The
// minimizer dg is the radial return's equivalent plastic strain increment, (q - yield) /
// (3 mu + hardening) with q = sqrt(6) mu s the trial von Mises stress, and by the envelope
// theorem G'(s) = 2 mu s*, s* = s - sqrt(3/2) dg the returned deviator's norm: the returned
// stress. G is convex and C1 in s; G'' is 2 mu inside the yield surface and
// 2 mu hardening / (3 mu + hardening) past it.
struct DeviatoricFlow {
  double energy;         // G(s)
  double slopeOverS;     // G'(s) / s (2 mu at s = 0)
  double curvature;      // G''(s)
  double plasticStrain;  // dg
  double keptFraction;   // s* / s: the part of the deviator that stays elastic
};

GALSCULPT_HD DeviatoricFlow deviatoricFlow(double mu, double yield, double hardening, double s) {
  const double q = sqrt(6.0) * mu * s;
  if (!(yield > 0.0) || q <= yield) return {mu * s * s, 2.0 * mu, 2.0 * mu, 0.0, 1.0};
  const double dg = (q - yield) / (3.0 * mu + hardening);
  const double kept = s - sqrt(1.5) * dg;
  return {mu * kept * kept + yield * dg + 0.5 * hardening * dg * dg, 2.0 * mu * kept / s,
          2.0 * mu * hardening / (3.0 * mu + hardening), dg, kept / s};
}

// The Hencky strain e_i = l(s_i) of singular values s, its trace and deviator d with norm.
struct HenckyStrain {
  ExtendedLog log[3];
  double trace;
  double deviator[3];
  double deviatorNorm;
};

GALSCULPT_HD HenckyStrain henckyStrain(const double s[3]) {
  HenckyStrain h;
  for (int i = 0; i < 3; ++i) h.log[i] = extendedLog(s[i]);
  h.trace = h.log[0].value + h.log[1].value + h.log[2].value;
  double norm2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    h.deviator[i] = h.log[i].value - h.trace / 3.0;
    norm2 += h.deviator[i] * h.deviator[i];
  }
  h.deviatorNorm = sqrt(norm2);
  return h;
}

// Whether the elastic part `fe` is clearly inside the yield surface: its Hencky deviator's norm
// under `margin` of the yield strain yield / (sqrt(6) mu). The return map's first test, from the
// eigenvalues of fe^T fe in closed form (Cardano) instead of an SVD: most elements of a body do
// not flow, and the SVD was most of the return's cost. False (not decided: take the SVD) for a
// collapsed or inverted element, whose strain is the continued logarithm's.
GALSCULPT_HD bool clearlyElastic(const M3& fe, double mu, double yield, double margin) {
  if (!(yield > 0.0)) return true;
  if (!(determinant(fe) > 0.0)) return false;
  CardanoRoots roots;
  if (!cardanoRoots(multiply(transpose(fe), fe), roots)) return false;
  double lambda[3];  // the eigenvalues of fe^T fe: the squared stretches
  for (int i = 0; i < 3; ++i) lambda[i] = roots.shift + roots.scale * roots.t[i];
  constexpr double floorSquared = kLogStretchFloor * kLogStretchFloor;
  if (!(fmin(lambda[0], fmin(lambda[1], lambda[2])) > floorSquared)) return false;
  double e[3];
  for (int i = 0; i < 3; ++i) e[i] = 0.5 * log(lambda[i]);
  const double mean = (e[0] + e[1] + e[2]) / 3.0;
  double norm2 = 0.0;
  for (int i = 0; i < 3; ++i) norm2 += (e[i] - mean) * (e[i] - mean);
  return sqrt(6.0) * mu * sqrt(norm2) < margin * yield;
}

}  // namespace galsculpt::kernels
