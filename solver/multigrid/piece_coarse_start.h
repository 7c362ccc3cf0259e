// The coarsest level's start with two or more pieces (multigrid_cycle.h): each piece's exact
// affine solution, from its 12x12 system in the piece's affine modes (the layout's pieceMap), so
// that the coarse CG only corrects within pieces. Factored at each refresh, solved at each
// coarsest solve; launches of an executor, no host waits.
#pragma once

#include <cmath>

#include "solver/fem/dense_kernels.h"
#include "solver/multigrid/multigrid_layout.h"

namespace galsculpt {

template <typename Exec>
class PieceCoarseStart {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  explicit PieceCoarseStart(Exec& ex) : ex_(ex) {}

  // Mirrors the layout's pieces (none with fewer than two).
  void upload(const MultigridLayout& m) {
    count_ = m.pieceCount;
    if (count_ < 2) return;
    pieceOfHandle_.upload(m.pieceOfHandle);
    map_.upload(m.pieceMap);
    contribStart_.upload(m.pieceContribStart);
    contribBlock_.upload(m.pieceContribBlock);
    contribRow_.upload(m.pieceContribRow);
    handleStart_.upload(m.pieceHandleStart);
    handles_.upload(m.pieceHandles);
    factor_.resize(144 * static_cast<size_t>(count_));
    solution_.resize(12 * static_cast<size_t>(count_));
  }

  bool active() const { return count_ >= 2; }

  // Each piece's operator in its modes from the coarsest level's blocks (and its columns),
  // regularized by 1e-12 of its mean diagonal and factored.
  void factorize(const int* columns, const double* blocks) {
    const int* start = contribStart_.data();
    const int* block = contribBlock_.data();
    const int* row = contribRow_.data();
    const double* map = map_.data();
    double* factor = factor_.data();
    ex_.forEach(count_, [=] GALSCULPT_LAMBDA(int q) {
      double m[144] = {};
      for (int i = start[q]; i < start[q + 1]; ++i) {
        const int k = block[i], h = row[i], g = columns[k];
        addTripleProduct12(map + 144 * h, blocks + 144 * k, map + 144 * g, m);
      }
      double trace = 0.0;
      for (int i = 0; i < 12; ++i) trace += m[13 * i];
      for (int i = 0; i < 12; ++i) m[13 * i] += 1e-12 * fmax(trace / 12.0, 1e-300);
      cholesky(12, m);
      for (int i = 0; i < 144; ++i) factor[144 * q + i] = m[i];
    });
  }

  // x (the coarsest level's `handles` handles) = each piece's affine solution for b.
  void solve(int handles, const double* b, double* x) {
    const int* hStart = handleStart_.data();
    const int* members = handles_.data();
    const int* pieceOf = pieceOfHandle_.data();
    const double* map = map_.data();
    const double* factor = factor_.data();
    double* e = solution_.data();
    ex_.forEach(count_, [=] GALSCULPT_LAMBDA(int q) {
      double rhs[12] = {};
      for (int i = hStart[q]; i < hStart[q + 1]; ++i) {
        const int h = members[i];
        addMultiplyTransposed12(map + 144 * h, b + 12 * h, rhs);
      }
      choleskySolve(12, factor + 144 * q, rhs);
      for (int k = 0; k < 12; ++k) e[12 * q + k] = rhs[k];
    });
    ex_.forEach(handles, [=] GALSCULPT_LAMBDA(int h) {
      double out[12] = {};
      addMultiply12(map + 144 * h, e + 12 * pieceOf[h], out);
      for (int k = 0; k < 12; ++k) x[12 * h + k] = out[k];
    });
  }

 private:
  Exec& ex_;
  int count_ = 0;
  Buffer<int> pieceOfHandle_, contribStart_, contribBlock_, contribRow_, handleStart_, handles_;
  Buffer<double> map_, factor_, solution_;
};

}  // namespace galsculpt
