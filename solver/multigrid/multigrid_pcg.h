// Conjugate gradients on the fine system A x = b preconditioned by one V-cycle of the Galerkin
// multigrid per iteration (multigrid_cycle.h), from x = 0, until |r| <= max(tolerance |b|,
// absoluteTarget) or maxIterations. Its scalars are read by the host every iteration (alpha,
// beta, the stopping test), so it is not captured as a graph; the V-cycles inside are plain
// launches.
#pragma once

#include <algorithm>
#include <cmath>

#include "solver/fem/dense_kernels.h"

namespace galsculpt {

template <typename Exec>
class MultigridPcg {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  struct Result {
    double reduction = 0.0;  // |r| / |b| (0 for b = 0)
    int iterations = 0;
  };

  explicit MultigridPcg(Exec& ex) : ex_(ex) {}

  // `cycle`: its vcycle(a, 0, r, z, s) is the preconditioner, multiplyFine(a, p, ap) the
  // operator; `rows`: the fine level's.
  template <typename Cycle>
  Result solve(Cycle& cycle, int rows, const double* a, const double* b, double* x,
               const typename Cycle::Settings& s, double tolerance, int maxIterations,
               double absoluteTarget) {
    const int n = 3 * rows;
    if (r_.size() != static_cast<size_t>(n)) {
      for (Buffer<double>* v : {&r_, &z_, &p_, &ap_}) v->resize(n);
      scalars_.resize(1);
    }
    double* r = r_.data();
    double* z = z_.data();
    double* p = p_.data();
    double* ap = ap_.data();
    Scalars* sc = scalars_.data();
    Scalars read;
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
      x[i] = 0.0;
      r[i] = b[i];
      z[i] = 0.0;
    });
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return b[i] * b[i]; }, &sc->bb);
    cycle.vcycle(a, 0, r, z, s);
    ex_.copy(p, z, n);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * z[i]; }, &sc->rz);
    ex_.read(sc, &read, 1);
    const double bnorm = std::sqrt(read.bb);
    const double target = std::max(tolerance * std::max(bnorm, 1e-300), absoluteTarget);
    double rz = read.rz, rnorm = bnorm;
    int it = 0;
    for (; it < maxIterations && rnorm > target; ++it) {
      cycle.multiplyFine(a, p, ap);
      ex_.sum(
          n, [=] GALSCULPT_LAMBDA(int i) { return p[i] * ap[i]; }, &sc->pap);
      ex_.read(sc, &read, 1);
      if (!(read.pap > 0.0)) break;
      const double alpha = rz / read.pap;
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * ap[i];
      });
      ex_.sum(
          n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * r[i]; }, &sc->rr);
      ex_.read(sc, &read, 1);
      rnorm = std::sqrt(read.rr);
      if (rnorm <= target) {
        ++it;
        break;
      }
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) { z[i] = 0.0; });
      cycle.vcycle(a, 0, r, z, s);
      ex_.sum(
          n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * z[i]; }, &sc->rz);
      ex_.read(sc, &read, 1);
      const double beta = read.rz / rz;
      rz = read.rz;
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) { p[i] = z[i] + beta * p[i]; });
    }
    return {bnorm > 0.0 ? rnorm / bnorm : 0.0, it};
  }

  // What the host reads: |b|^2, r.z, p.Ap, |r|^2.
  struct Scalars {
    double bb = 0.0, rz = 0.0, pap = 0.0, rr = 0.0;
  };

 private:
  Exec& ex_;
  Buffer<double> r_, z_, p_, ap_;  // allocated on the first solve
  Buffer<Scalars> scalars_;
};

}  // namespace galsculpt
