// Conjugate gradients on the fine system A x = b preconditioned by one V-cycle of the Galerkin
// multigrid per iteration (multigrid_cycle.h), from x = 0, until |r| <= max(tolerance |b|,
// absoluteTarget) or maxIterations. Its scalars stay in executor memory: alpha and beta are
// formed by the launches that use them, and the stopping test by a one-thread launch that
// freezes the iteration once it holds (x, r and p then stay as they were), so the host reads
// only the state. In host memory it reads it after every iteration and stops there, as a host
// loop would; on a device it runs iterations in batches sized by the residual's rate so far and
// reads once a batch (the iterations a batch runs past the stop change nothing): a host wait per
// batch, not three per iteration. The arithmetic is the same either way, to the bit.
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

  // The solve's scalars in executor memory: |b|^2, r.z (the last iteration's and the one before,
  // by the iteration's parity: no launch copies one to the other), p.Ap, |r|^2 and the next |r|^2
  // (before the stop decides whether it counts), the stop's target, the iterations done and
  // whether it still runs (1) or stopped (0).
  struct Scalars {
    double bb = 0.0, rz[2] = {0.0, 0.0}, pap = 0.0, rr = 0.0, rrNext = 0.0;
    double target = 0.0, iterations = 0.0, running = 0.0;
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
    Scalars* sc = scalars_.data();
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
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * z[i]; }, &sc->rz[0]);
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      const double bnorm = sqrt(sc->bb);
      sc->target = fmax(tolerance * fmax(bnorm, 1e-300), absoluteTarget);
      sc->rr = sc->bb;
      sc->iterations = 0.0;
      sc->running = maxIterations > 0 && bnorm > sc->target ? 1.0 : 0.0;
    });
    Scalars read;
    int launched = 0;  // iterations launched (those past the stop change nothing)
    if constexpr (Exec::kHostMemory) {
      ex_.read(sc, &read, 1);
      for (; read.running != 0.0 && launched < maxIterations; ++launched) {
        step(cycle, n, a, x, maxIterations, launched);
        ex_.read(sc, &read, 1);  // a host loop's test: it stops without the new direction
        if (read.running != 0.0) direction(cycle, n, a, s, launched);
      }
    } else {
      // A short first batch (at most 2, and one less than the shorter of the last two solves: a
      // sub-step's Newton iterations alternate long solves and solves of one or two), then each
      // batch as long as the rate seen so far says is left.
      const int shorter = std::min(lastIterations_[0], lastIterations_[1]);
      int batch = fixedBatch_ > 0 ? fixedBatch_ : std::clamp(shorter - 1, 1, kBatch);
      for (;;) {
        const int until = std::min(maxIterations, launched + batch);
        for (; launched < until; ++launched) {
          step(cycle, n, a, x, maxIterations, launched);
          direction(cycle, n, a, s, launched);
        }
        ex_.read(sc, &read, 1);
        if (read.running == 0.0 || launched >= maxIterations) break;
        batch = fixedBatch_ > 0 ? fixedBatch_ : batchLeft(read);
      }
    }
    const int iterations = static_cast<int>(read.iterations);
    lastIterations_[1] = lastIterations_[0];
    lastIterations_[0] = iterations;
    const double bnorm = std::sqrt(read.bb);
    return {bnorm > 0.0 ? std::sqrt(read.rr) / bnorm : 0.0, iterations};
  }

  // The iterations a running solve still needs by the mean rate of its residual so far, within
  // 1 .. kLongestBatch.
  static int batchLeft(const Scalars& read) {
    const double bnorm = std::sqrt(read.bb), rnorm = std::sqrt(read.rr);
    if (!(read.iterations > 0.0 && rnorm > 0.0 && rnorm < bnorm)) return kBatch;
    const double rate = std::pow(rnorm / bnorm, 1.0 / read.iterations);
    if (!(rate < 1.0)) return kBatch;
    const double left = std::ceil(std::log(read.target / rnorm) / std::log(rate));
    return static_cast<int>(std::clamp(left, 1.0, double(kLongestBatch)));
  }

  // An iteration's step, steered by the scalars in executor memory: nothing changes once
  // `running` is 0. x and r move along p; p.Ap <= 0 stops the solve before that (the iteration
  // not counted), |r| <= target or the last iteration after it. The stop is decided by the
  // launch that clears z for the preconditioner (its first thread), so it costs no launch.
  template <typename Cycle>
  void step(Cycle& cycle, int n, const double* a, double* x, int maxIterations, int k) {
    const int was = k & 1;
    double* r = r_.data();
    double* z = z_.data();
    double* p = p_.data();
    double* ap = ap_.data();
    Scalars* sc = scalars_.data();
    cycle.multiplyFine(a, p, ap);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return p[i] * ap[i]; }, &sc->pap);
    if constexpr (Exec::kHostMemory) {
      // Host memory reads its scalars for nothing: alpha is formed once, not for every entry.
      Scalars now;
      ex_.read(sc, &now, 1);
      if (now.running != 0.0 && now.pap > 0.0) {
        const double alpha = now.rz[was] / now.pap;
        ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
          x[i] += alpha * p[i];
          r[i] -= alpha * ap[i];
        });
      }
    } else {
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
        if (sc->running == 0.0 || !(sc->pap > 0.0)) return;
        const double alpha = sc->rz[was] / sc->pap;
        x[i] += alpha * p[i];
        r[i] -= alpha * ap[i];
      });
    }
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * r[i]; }, &sc->rrNext);
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
      z[i] = 0.0;
      if (i != 0 || sc->running == 0.0) return;
      if (!(sc->pap > 0.0)) {
        sc->running = 0.0;
        return;
      }
      sc->rr = sc->rrNext;
      sc->iterations += 1.0;
      if (sqrt(sc->rr) <= sc->target || sc->iterations >= maxIterations) sc->running = 0.0;
    });
  }

  // The iteration's new direction: z = V-cycle(r), p = z + (r.z / last r.z) p (`k`: the
  // iteration's number, whose parity picks the slots of r.z).
  template <typename Cycle>
  void direction(Cycle& cycle, int n, const double* a, const typename Cycle::Settings& s, int k) {
    const int was = k & 1, now = 1 - was;
    double* r = r_.data();
    double* z = z_.data();
    double* p = p_.data();
    Scalars* sc = scalars_.data();
    cycle.vcycle(a, 0, r, z, s);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * z[i]; }, &sc->rz[now]);
    if constexpr (Exec::kHostMemory) {  // (only while running: the host stopped before)
      Scalars read;
      ex_.read(sc, &read, 1);
      const double beta = read.rz[now] / read.rz[was];
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) { p[i] = z[i] + beta * p[i]; });
    } else {
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
        if (sc->running != 0.0) p[i] = z[i] + sc->rz[now] / sc->rz[was] * p[i];
      });
    }
  }

  // Every batch `iterations` long instead of by the rate (0: by the rate; tests).
  void setFixedBatch(int iterations) { fixedBatch_ = iterations; }

  // A device's batches: at most kLongestBatch iterations; kBatch where no rate is known yet.
  static constexpr int kLongestBatch = 8, kBatch = 2;

 private:
  Exec& ex_;
  Buffer<double> r_, z_, p_, ap_;  // allocated on the first solve
  Buffer<Scalars> scalars_;
  int lastIterations_[2] = {1, 1};  // the last two solves' iterations (a device's first batch)
  int fixedBatch_ = 0;
};

}  // namespace galsculpt
