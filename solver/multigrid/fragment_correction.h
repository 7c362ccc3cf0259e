// The fine level's fragment corrections of the Galerkin multigrid (multigrid_cycle.h): a small
// piece the damage has cut off (a fragment, multigrid_layout.h) has no coarse handle of its own
// that moves it alone, so after the coarse correction each fragment is corrected in its own
// affine modes [(X - c)/s, 1] (or its translation, where those are singular), a Galerkin
// projection of the residual of all fragment vertices taken before any of them moves.
#pragma once

#include <cmath>
#include <cstdint>

#include "solver/fem/dense_kernels.h"
#include "solver/multigrid/multigrid_layout.h"

namespace galsculpt {

template <typename Exec>
class FragmentCorrection {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  explicit FragmentCorrection(Exec& ex) : ex_(ex) {}

  // Mirrors the layout's fragments (`rows`: the fine level's).
  void upload(const MultigridLayout& m, int rows) {
    rows_ = rows;
    fragments_ = static_cast<int>(m.fragmentStart.size()) - 1;
    if (fragments_ <= 0) return;
    fragmentStart_.upload(m.fragmentStart);
    fragmentVertices_.upload(m.fragmentVertices);
    fragmentOf_.upload(m.fragmentOf);
    fragmentFrame_.upload(m.fragmentFrame);
    restPositions_.upload(m.restPositions);
    fragmentFactor_.resize(144 * static_cast<size_t>(fragments_));
    fragmentPerm_.resize(12 * static_cast<size_t>(fragments_));
    fragmentTranslation_.resize(9 * static_cast<size_t>(fragments_));
    fragmentMode_.resize(fragments_);
    if (residual_.size() != 3 * static_cast<size_t>(rows)) residual_.resize(3 * rows);
  }

  int fragments() const { return fragments_ > 0 ? fragments_ : 0; }

  // Fragment f's affine modes at vertex v: [(X_v - c_f) / s_f, 1].
  GALSCULPT_HD static void fragmentModes(const double* frame, const double* rest, int v,
                                         double* y) {
    for (int k = 0; k < 3; ++k) y[k] = (rest[3 * v + k] - frame[k]) / frame[3];
    y[3] = 1.0;
  }

  // Each fragment's 12x12 operator in its modes from the fine blocks `a` (the fine pattern's
  // rowStart and columns), factored (or its translation's 3x3, where the modes are singular).
  void factorize(const double* a, const int* rowStart, const int* columns) {
    const int* start = fragmentStart_.data();
    const int* vertices = fragmentVertices_.data();
    const int* fragmentOf = fragmentOf_.data();
    const double* frames = fragmentFrame_.data();
    const double* rest = restPositions_.data();
    double* factor = fragmentFactor_.data();
    int* perm = fragmentPerm_.data();
    double* translation = fragmentTranslation_.data();
    std::uint8_t* mode = fragmentMode_.data();
    ex_.forEach(fragments_, [=] GALSCULPT_LAMBDA(int f) {
      double m[144] = {};
      const double* frame = frames + 4 * f;
      // Row by row: the row's blocks against the column modes first (36 multiply-adds a block),
      // then the row's mode once (144), where the Kronecker product of each block took 144.
      for (int i = start[f]; i < start[f + 1]; ++i) {
        const int r = vertices[i];
        double row[36] = {};
        for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
          const int c = columns[k];
          if (fragmentOf[c] != f) continue;
          double yc[4];
          fragmentModes(frame, rest, c, yc);
          addBlockTimesModes(yc, a + 9 * k, row);
        }
        double yr[4];
        fragmentModes(frame, rest, r, yr);
        addModesTimesRow(yr, row, m);
      }
      double trace = 0.0;
      for (int i = 0; i < 12; ++i) trace += m[13 * i];
      double* t = translation + 9 * f;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) t[i + 3 * j] = m[(9 + i) + 12 * (9 + j)];
      const bool translationOk = cholesky(3, t);
      double* l = factor + 144 * f;
      for (int i = 0; i < 144; ++i) l[i] = m[i];
      bool affine = start[f + 1] - start[f] >= 4 && ldlt12(l, perm + 12 * f);
      for (int i = 0; affine && i < 12; ++i) affine = l[13 * i] > 1e-12 * trace;
      mode[f] = affine ? 2 : (translationOk ? 1 : 0);
    });
  }

  // Galerkin correction of each fragment in its own affine modes (or its translation), from the
  // residual of all fragment vertices taken before any moves.
  void correct(const double* a, const int* rowStart, const int* columns, const double* b,
               double* x) {
    const int* start = fragmentStart_.data();
    const int* vertices = fragmentVertices_.data();
    const int* fragmentOf = fragmentOf_.data();
    const double* frames = fragmentFrame_.data();
    const double* rest = restPositions_.data();
    const double* factor = fragmentFactor_.data();
    const int* perm = fragmentPerm_.data();
    const double* translation = fragmentTranslation_.data();
    const std::uint8_t* mode = fragmentMode_.data();
    double* residual = residual_.data();
    ex_.forEach(rows_, [=] GALSCULPT_LAMBDA(int r) {
      if (fragmentOf[r] < 0) return;
      double res[3] = {b[3 * r], b[3 * r + 1], b[3 * r + 2]};
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
        subtractMultiply3(a + 9 * k, x + 3 * columns[k], res);
      for (int i = 0; i < 3; ++i) residual[3 * r + i] = res[i];
    });
    ex_.forEach(fragments_, [=] GALSCULPT_LAMBDA(int f) {
      if (mode[f] == 0) return;
      const double* frame = frames + 4 * f;
      double rhs[12] = {};
      for (int i = start[f]; i < start[f + 1]; ++i) {
        const int r = vertices[i];
        double y[4];
        fragmentModes(frame, rest, r, y);
        for (int j = 0; j < 4; ++j)
          for (int k = 0; k < 3; ++k) rhs[3 * j + k] += y[j] * residual[3 * r + k];
      }
      double e[12] = {};
      if (mode[f] == 2) {
        ldlt12Solve(factor + 144 * f, perm + 12 * f, rhs, e);
      } else {
        double t[3] = {rhs[9], rhs[10], rhs[11]};
        choleskySolve(3, translation + 9 * f, t);
        for (int k = 0; k < 3; ++k) e[9 + k] = t[k];
      }
      for (double value : e)
        if (!(value == value) || fabs(value) > 1e300) return;
      for (int i = start[f]; i < start[f + 1]; ++i) {
        const int v = vertices[i];
        double y[4];
        fragmentModes(frame, rest, v, y);
        for (int j = 0; j < 4; ++j)
          for (int k = 0; k < 3; ++k) x[3 * v + k] += y[j] * e[3 * j + k];
      }
    });
  }

 private:
  Exec& ex_;
  int rows_ = 0, fragments_ = 0;
  Buffer<int> fragmentStart_, fragmentVertices_, fragmentOf_, fragmentPerm_;
  Buffer<double> fragmentFrame_, restPositions_, fragmentFactor_, fragmentTranslation_, residual_;
  Buffer<std::uint8_t> fragmentMode_;
};

}  // namespace galsculpt
