// Quasi-Newton directions (L-BFGS; Liu, Bouaziz and Kavan 2017, "Quasi-Newton Methods for
// Real-Time Simulation of Hyperelastic Materials"): the sub-step's last few steps s = x_{k+1} -
// x_k and gradient changes y = g_{k+1} - g_k correct an initial inverse H0^-1 by the two-loop
// recursion,
//   q = b;  for i newest..oldest: a_i = rho_i s_i.q,  q -= a_i y_i
//   z = H0^-1 q
//   for i oldest..newest: c = rho_i y_i.z,  z += (a_i - c) s_i          (rho_i = 1 / s_i.y_i)
// so that the step z is what BFGS's inverse update of H0 by those pairs would give for b = -g.
// H0 is the Newton matrix the sub-step last assembled, solved by the multigrid (the frame's
// linear solve): where a chord step solves with that matrix alone, the pairs carry what the
// gradient did since (strains that stiffened, crack faces that closed).
//
// g is the backward-Euler gradient, zero on held rows, so each pair is too. A pair whose
// curvature s.y is not clearly positive (s.y <= kCurvature |s| |y|) is kept with rho = 0: it
// changes nothing, and the inverse stays positive definite. Pairs live within a sub-step only
// (clear): a frame's result follows from its state. Every sum is the executor's fixed-order
// reduction, and the coefficients stay in executor memory (no host read), so the recursion is
// the same bits at any thread count and can be captured on a GPU.
#pragma once

#include <cmath>
#include <cstddef>

#include "solver/fem/dense_kernels.h"  // GALSCULPT_LAMBDA

namespace galsculpt {

template <typename Exec>
class SecantHistory {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  static constexpr double kCurvature = 1e-8;

  // `dofs`: 3 n. `pairs`: how many to keep, at least 1 (the option allows 8; Liu et al. keep
  // 5-7); older ones are dropped.
  SecantHistory(Exec& ex, int dofs, int pairs) : ex_(ex), dofs_(dofs), capacity_(pairs) {
    s_.resize(static_cast<size_t>(capacity_) * dofs_);
    y_.resize(static_cast<size_t>(capacity_) * dofs_);
    lastX_.resize(dofs_);
    lastG_.resize(dofs_);
    coefficients_.resize(4 * static_cast<size_t>(capacity_));
  }

  int capacity() const { return capacity_; }
  // Pairs recorded since clear (at most capacity()).
  int pairs() const { return count_; }
  // Pairs recorded since clear, the dropped ones too: what a captured recursion bakes in.
  int recorded() const { return recorded_; }

  void clear() {
    count_ = 0;
    recorded_ = 0;
    haveLast_ = false;
  }

  // The gradient `g` at `x` (3n each): with a point recorded before, the pair between the two
  // is kept (its rho 0 where its curvature is not positive). Then (x, g) is the last point.
  void record(const double* x, const double* g) {
    double* lastX = lastX_.data();
    double* lastG = lastG_.data();
    if (haveLast_) {
      const int slot = recorded_ % capacity_;
      double* s = s_.data() + static_cast<size_t>(slot) * dofs_;
      double* y = y_.data() + static_cast<size_t>(slot) * dofs_;
      ex_.forEach(dofs_, [=] GALSCULPT_LAMBDA(int i) {
        s[i] = x[i] - lastX[i];
        y[i] = g[i] - lastG[i];
      });
      double* c = coefficients_.data() + 4 * slot;
      ex_.sum(
          dofs_, [=] GALSCULPT_LAMBDA(int i) { return s[i] * y[i]; }, c + 2);
      ex_.sum(
          dofs_, [=] GALSCULPT_LAMBDA(int i) { return s[i] * s[i]; }, c + 1);
      ex_.sum(
          dofs_, [=] GALSCULPT_LAMBDA(int i) { return y[i] * y[i]; }, c + 3);
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
        const double sy = c[2];
        c[0] = sy > kCurvature * sqrt(c[1]) * sqrt(c[3]) ? 1.0 / sy : 0.0;
      });
      ++recorded_;
      if (count_ < capacity_) ++count_;
    }
    ex_.copy(lastX, x, static_cast<size_t>(dofs_));
    ex_.copy(lastG, g, static_cast<size_t>(dofs_));
    haveLast_ = true;
  }

  // The recursion's first loop, on `q` in place (b = -g on entry; the right-hand side of H0's
  // solve on return).
  void firstLoop(double* q) {
    for (int k = 0; k < count_; ++k) {
      const int slot = slotOf(count_ - 1 - k);
      const double* s = s_.data() + static_cast<size_t>(slot) * dofs_;
      const double* y = y_.data() + static_cast<size_t>(slot) * dofs_;
      double* c = coefficients_.data() + 4 * slot;
      ex_.sum(
          dofs_, [=] GALSCULPT_LAMBDA(int i) { return s[i] * q[i]; }, c + 1);
      ex_.forEach(dofs_, [=] GALSCULPT_LAMBDA(int i) { q[i] -= c[0] * c[1] * y[i]; });
    }
  }

  // The second loop, on H0's solution `z` in place: the step.
  void secondLoop(double* z) {
    for (int k = 0; k < count_; ++k) {
      const int slot = slotOf(k);
      const double* s = s_.data() + static_cast<size_t>(slot) * dofs_;
      const double* y = y_.data() + static_cast<size_t>(slot) * dofs_;
      double* c = coefficients_.data() + 4 * slot;
      ex_.sum(
          dofs_, [=] GALSCULPT_LAMBDA(int i) { return y[i] * z[i]; }, c + 3);
      ex_.forEach(dofs_,
                  [=] GALSCULPT_LAMBDA(int i) { z[i] += (c[0] * c[1] - c[0] * c[3]) * s[i]; });
    }
  }

 private:
  // The slot of the k-th oldest pair kept (0: the oldest).
  int slotOf(int k) const { return (recorded_ - count_ + k) % capacity_; }

  Exec& ex_;
  int dofs_, capacity_;
  int count_ = 0, recorded_ = 0;
  bool haveLast_ = false;
  Buffer<double> s_, y_, lastX_, lastG_;
  // Per slot: rho; |s|^2 while recording, then the first loop's a; s.y; |y|^2 while recording,
  // then the second loop's y.z.
  Buffer<double> coefficients_;
};

}  // namespace galsculpt
