// The terms of the incremental potential that act on each coordinate alone: backward Euler's
// inertia, gravity, Rayleigh damping and a soft anchor's spring (held_vertices.h). Each term
// gives, for coordinate i at positions y, its energy, its gradient and its coefficient of the
// mass on the Newton matrix's diagonal (or its own diagonal entry). IncrementalPotential sums the
// list below in its order, in one launch, beside the pass terms (the elements, element_pass.h;
// contact, contact_term.h). A left fold is the arithmetic of the expression written out, so the
// split into terms costs no bit.
//
// Adding a coordinate term: its struct here (energy, gradient, massCoefficient, diagonal; a
// finite-difference test in tests/solver/frame/coordinate_terms_test.cpp) and its place in
// CoordinateTermList.
#pragma once

#include "solver/fem/kernel_math.h"

namespace galsculpt {

// What the coordinate terms read at a sub-step: the inertial target x̂ = x_n + h v_n, the start
// x_n, the masses and springs per vertex, and βK₀(y - x_n) for the y at hand (dampedK).
struct CoordinateInputs {
  const double *xhat, *xn, *mass, *springK, *springTarget, *dampedK;
  double h, alpha, gravity[3];
  GALSCULPT_HD double m(int i) const { return mass[i / 3]; }
};

// m/(2h²) |y - x̂|²: the inertia of backward Euler.
struct InertiaTerm {
  GALSCULPT_HD static double energy(const CoordinateInputs& c, int i, const double* y) {
    const double d = y[i] - c.xhat[i];
    return 0.5 / (c.h * c.h) * d * (c.m(i) * d);
  }
  GALSCULPT_HD static double gradient(const CoordinateInputs& c, int i, const double* y) {
    return c.m(i) * (y[i] - c.xhat[i]) / (c.h * c.h);
  }
  GALSCULPT_HD static double massCoefficient(const CoordinateInputs& c) {
    return 1.0 / (c.h * c.h);
  }
  GALSCULPT_HD static double diagonal(const CoordinateInputs&, int) { return 0.0; }
};

// -m g·y: gravity's work.
struct GravityTerm {
  GALSCULPT_HD static double energy(const CoordinateInputs& c, int i, const double* y) {
    return -(c.m(i) * c.gravity[i % 3] * y[i]);
  }
  GALSCULPT_HD static double gradient(const CoordinateInputs& c, int i, const double*) {
    return -(c.m(i) * c.gravity[i % 3]);
  }
  GALSCULPT_HD static double massCoefficient(const CoordinateInputs&) { return 0.0; }
  GALSCULPT_HD static double diagonal(const CoordinateInputs&, int) { return 0.0; }
};

// 1/(2h) (α m |y - x_n|² + (y - x_n)·βK₀(y - x_n)): Rayleigh damping, its stiffness part frozen
// at the sub-step's start (its blocks are added by the system's build, βK₀/h).
struct DampingTerm {
  GALSCULPT_HD static double energy(const CoordinateInputs& c, int i, const double* y) {
    const double dx = y[i] - c.xn[i];
    return 0.5 / c.h * (c.alpha * dx * (c.m(i) * dx) + dx * c.dampedK[i]);
  }
  GALSCULPT_HD static double gradient(const CoordinateInputs& c, int i, const double* y) {
    return (c.alpha * (c.m(i) * (y[i] - c.xn[i])) + c.dampedK[i]) / c.h;
  }
  GALSCULPT_HD static double massCoefficient(const CoordinateInputs& c) { return c.alpha / c.h; }
  GALSCULPT_HD static double diagonal(const CoordinateInputs&, int) { return 0.0; }
};

// k/2 |y - t|²: a soft anchor's spring (a brush's hold), zero on most vertices.
struct SpringTerm {
  GALSCULPT_HD static double energy(const CoordinateInputs& c, int i, const double* y) {
    const double k = c.springK[i / 3];
    if (!(k > 0.0)) return 0.0;
    const double s = y[i] - c.springTarget[i];
    return 0.5 * k * s * s;
  }
  GALSCULPT_HD static double gradient(const CoordinateInputs& c, int i, const double* y) {
    const double k = c.springK[i / 3];
    return k > 0.0 ? k * (y[i] - c.springTarget[i]) : 0.0;
  }
  GALSCULPT_HD static double massCoefficient(const CoordinateInputs&) { return 0.0; }
  GALSCULPT_HD static double diagonal(const CoordinateInputs& c, int vertex) {
    return c.springK[vertex] > 0.0 ? c.springK[vertex] : 0.0;
  }
};

template <typename... Terms>
struct CoordinateTermList {
  // The energy of coordinate i: the terms in order.
  GALSCULPT_HD static double energy(const CoordinateInputs& c, int i, const double* y) {
    return (... + Terms::energy(c, i, y));  // a left fold: ((t0 + t1) + t2) + ...
  }
  // The gradient of coordinate i with `force`, the pass terms' (elastic and contact), added
  // after the first term: its place in the sum is part of the frame's pinned bits.
  template <typename First, typename... Rest>
  GALSCULPT_HD static double gradientAfter(const CoordinateInputs& c, int i, const double* y,
                                           double force) {
    return ((First::gradient(c, i, y) + force) + ... + Rest::gradient(c, i, y));
  }
  GALSCULPT_HD static double gradient(const CoordinateInputs& c, int i, const double* y,
                                      double force) {
    return gradientAfter<Terms...>(c, i, y, force);
  }
  // The mass's coefficient on the diagonal (1/h² + α/h) and the terms' own diagonal entries.
  GALSCULPT_HD static double massCoefficient(const CoordinateInputs& c) {
    return (... + Terms::massCoefficient(c));
  }
  GALSCULPT_HD static double diagonal(const CoordinateInputs& c, int vertex) {
    return (... + Terms::diagonal(c, vertex));
  }
};

// The incremental potential's coordinate terms, in the order of their sums.
using CoordinateTerms = CoordinateTermList<InertiaTerm, GravityTerm, DampingTerm, SpringTerm>;

}  // namespace galsculpt
