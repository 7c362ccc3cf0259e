// Conjugate gradients on the fine system A x = b preconditioned by one V-cycle of the Galerkin
// multigrid per iteration (multigrid_cycle.h), from x = 0, until |r| <= max(tolerance |b|,
// absoluteTarget) or maxIterations. Its scalars stay in executor memory: alpha and beta are
// formed by the launches that use them, and the stopping test by a one-thread launch that
// freezes the iteration once it holds (x, r and p then stay as they were), so the host reads
// only the state. In host memory it reads it after every iteration and stops there, as a host
// loop would. On a device the iterations are a loop whose test the device makes
// (Exec::loopOnDevice: a CUDA graph with a while node on `running`): every iteration is the same
// launches, and the host waits for nothing until it reads the result, or not at all where a
// caller folds the result into a read of its own (launch()). The arithmetic is the same either
// way, to the bit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "solver/fem/dense_kernels.h"
#include "solver/fem/launch_key.h"

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

  // The solve's scalars in executor memory: |b|^2, r.z (this iteration's, which alpha divides,
  // and the one before, which beta divides by: the stop's launch moves the one to the other,
  // after alpha's launch read it), p.Ap, |r|^2 and the next |r|^2 (before the stop decides
  // whether it counts), the stop's target, the iterations done and whether it still runs (1) or
  // stopped (0). Every iteration's launches are the same, whatever its number: a device replays
  // them as one loop.
  struct Scalars {
    double bb = 0.0, rz = 0.0, rzLast = 0.0, pap = 0.0, rr = 0.0, rrNext = 0.0;
    double target = 0.0, iterations = 0.0, running = 0.0;
  };

  explicit MultigridPcg(Exec& ex) : ex_(ex) {}

  // `cycle`: its vcycle(a, 0, r, z, s) is the preconditioner, multiplyFine(a, p, ap) the
  // operator; `rows`: the fine level's. `bakedKey`: what the cycle's launches bake in besides the
  // arguments (its buffers and host-side choices: MultigridCycle::bakedKey), so that a device
  // replays its loop only while none of it changed.
  template <typename Cycle>
  Result solve(Cycle& cycle, int rows, const double* a, const double* b, double* x,
               const typename Cycle::Settings& s, double tolerance, int maxIterations,
               double absoluteTarget, std::uint64_t bakedKey = 0) {
    launch(cycle, rows, a, b, x, s, tolerance, maxIterations, absoluteTarget, bakedKey);
    Scalars read;
    ex_.read(scalars_.data(), &read, 1);
    return result(read);
  }

  // The solve without its read: x and the scalars (scalars()) as solve() leaves them, for a
  // caller that reads them later with its own (result() then makes the Result). In host memory
  // the iterations still read their state (a host loop).
  template <typename Cycle>
  void launch(Cycle& cycle, int rows, const double* a, const double* b, double* x,
              const typename Cycle::Settings& s, double tolerance, int maxIterations,
              double absoluteTarget, std::uint64_t bakedKey = 0) {
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
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * z[i]; }, &sc->rz);
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      const double bnorm = sqrt(sc->bb);
      sc->target = fmax(tolerance * fmax(bnorm, 1e-300), absoluteTarget);
      sc->rr = sc->bb;
      sc->iterations = 0.0;
      sc->running = maxIterations > 0 && bnorm > sc->target ? 1.0 : 0.0;
    });
    if constexpr (Exec::kHostMemory) {
      Scalars read;
      ex_.read(sc, &read, 1);
      for (int k = 0; read.running != 0.0 && k < maxIterations; ++k) {
        step(cycle, n, a, x, maxIterations);
        ex_.read(sc, &read, 1);  // a host loop's test: it stops without the new direction
        if (read.running != 0.0) direction(cycle, n, a, s);
      }
    } else {
      const std::uint64_t key = LaunchKey()
                                    .mix(bakedKey)
                                    .mix(static_cast<std::uint64_t>(n))
                                    .mix(static_cast<std::uint64_t>(maxIterations))
                                    .mixPointer(a)
                                    .mixPointer(x)
                                    .mixPointer(r)
                                    .mixPointer(sc)
                                    .value();
      ex_.loopOnDevice(key, &sc->running, maxIterations, [&] {
        step(cycle, n, a, x, maxIterations);
        direction(cycle, n, a, s);
      });
    }
  }

  // The solve's scalars in executor memory (for a caller of launch()).
  const Scalars* scalars() const { return scalars_.data(); }

  // What the scalars after a solve say (GALSCULPT_HD: a caller may form it in a launch).
  GALSCULPT_HD static Result result(const Scalars& read) {
    const double bnorm = sqrt(read.bb);
    return {bnorm > 0.0 ? sqrt(read.rr) / bnorm : 0.0, static_cast<int>(read.iterations)};
  }

  // An iteration's step, steered by the scalars in executor memory: nothing changes once
  // `running` is 0. x and r move along p; p.Ap <= 0 stops the solve before that (the iteration
  // not counted), |r| <= target or the last iteration after it. The stop is decided by the
  // launch that clears z for the preconditioner (its first thread), so it costs no launch.
  template <typename Cycle>
  void step(Cycle& cycle, int n, const double* a, double* x, int maxIterations) {
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
        const double alpha = now.rz / now.pap;
        ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
          x[i] += alpha * p[i];
          r[i] -= alpha * ap[i];
        });
      }
    } else {
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
        if (sc->running == 0.0 || !(sc->pap > 0.0)) return;
        const double alpha = sc->rz / sc->pap;
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
      sc->rzLast = sc->rz;  // (alpha's launch has read it) beta's divisor; direction() forms rz
      sc->iterations += 1.0;
      if (sqrt(sc->rr) <= sc->target || sc->iterations >= maxIterations) sc->running = 0.0;
    });
  }

  // The iteration's new direction: z = V-cycle(r), p = z + (r.z / last r.z) p.
  template <typename Cycle>
  void direction(Cycle& cycle, int n, const double* a, const typename Cycle::Settings& s) {
    double* r = r_.data();
    double* z = z_.data();
    double* p = p_.data();
    Scalars* sc = scalars_.data();
    cycle.vcycle(a, 0, r, z, s);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return r[i] * z[i]; }, &sc->rz);
    if constexpr (Exec::kHostMemory) {  // (only while running: the host stopped before)
      Scalars read;
      ex_.read(sc, &read, 1);
      const double beta = read.rz / read.rzLast;
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) { p[i] = z[i] + beta * p[i]; });
    } else {
      ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
        if (sc->running != 0.0) p[i] = z[i] + sc->rz / sc->rzLast * p[i];
      });
    }
  }

 private:
  Exec& ex_;
  Buffer<double> r_, z_, p_, ap_;  // allocated on the first solve
  Buffer<Scalars> scalars_;
};

}  // namespace galsculpt
