// The linear solve of a local Newton iteration (local_region.h): conjugate gradients on the
// region's rows of the Newton system, every other vertex held still (buildSystem gave their rows
// and columns the held vertices' form, and the right-hand side is zero there), preconditioned by
// the inverses of the region rows' diagonal blocks. The region is a few rings around where the
// residual is, held at its rim: its slowest modes are short, so block Jacobi needs no coarse
// level, and no step of it (the operator's refresh, a product, the preconditioner) reads a row
// outside the region. The iterations are multigrid_pcg.h's.
#pragma once

#include <cstdint>

#include "solver/fem/dense_kernels.h"
#include "solver/fem/kernel_math.h"
#include "solver/fem/launch_key.h"
#include "solver/frame/frame_data.h"
#include "solver/multigrid/multigrid_pcg.h"

namespace galsculpt {

template <typename Exec>
class RegionSolve {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;
  struct Settings {};

  // The most iterations a region's solve takes (a region of a few hundred vertices takes tens).
  static constexpr int kMostIterations = 300;

  RegionSolve(Exec& ex, FrameData<Exec>& data) : ex_(ex), d_(data), pcg_(ex) {
    inverse_.resize(9 * static_cast<size_t>(data.n));
  }

  // x = A^-1 b on the region's rows (x = 0 elsewhere), to |r| <= max(tolerance |b|, target),
  // without a read: the result stays in pcgScalars() (MultigridPcg::launch).
  void launch(const double* a, const double* b, double* x, double tolerance, double target) {
    const std::uint8_t* region = d_.regionVertex.data();
    const int* diagonal = d_.diagonal.data();
    double* inverse = inverse_.data();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int r) {
      if (!region[r]) return;
      kernels::M3 m;
      for (int k = 0; k < 9; ++k) m.a[k] = a[9 * static_cast<size_t>(diagonal[r]) + k];
      const kernels::M3 inv = kernels::inverse(m);
      for (int k = 0; k < 9; ++k) inverse[9 * static_cast<size_t>(r) + k] = inv.a[k];
    });
    pcg_.launch(*this, d_.n, a, b, x, Settings{}, tolerance, kMostIterations, target, bakedKey());
  }
  const typename MultigridPcg<Exec>::Scalars* pcgScalars() const { return pcg_.scalars(); }

  // What the preconditioner's and the product's launches bake in (MultigridPcg's loop on a
  // device): the region's arrays (the region itself is their contents, not baked).
  std::uint64_t bakedKey() const {
    return LaunchKey()
        .mixPointer(d_.regionVertex.data())
        .mixPointer(d_.diagonal.data())
        .mixPointer(d_.rowStart.data())
        .mixPointer(d_.columns.data())
        .mixPointer(inverse_.data())
        .value();
  }

  // The preconditioner (MultigridPcg's name for it): z = D^-1 r on the region's rows.
  void vcycle(const double*, int, const double* r, double* z, const Settings&) {
    const std::uint8_t* region = d_.regionVertex.data();
    const double* inverse = inverse_.data();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
      if (region[v]) multiply3(inverse + 9 * static_cast<size_t>(v), r + 3 * v, z + 3 * v);
    });
  }

  // y = A x on the region's rows, 0 elsewhere (x is 0 there: the region's rows of A reach no
  // other column).
  void multiplyFine(const double* a, const double* x, double* y) {
    const std::uint8_t* region = d_.regionVertex.data();
    const int* rowStart = d_.rowStart.data();
    const int* columns = d_.columns.data();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int r) {
      double acc[3] = {0.0, 0.0, 0.0};
      if (region[r])
        for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
          double t[3];
          multiply3(a + 9 * static_cast<size_t>(k), x + 3 * columns[k], t);
          for (int i = 0; i < 3; ++i) acc[i] += t[i];
        }
      for (int i = 0; i < 3; ++i) y[3 * r + i] = acc[i];
    });
  }

 private:
  Exec& ex_;
  FrameData<Exec>& d_;
  MultigridPcg<Exec> pcg_;
  Buffer<double> inverse_;  // (9n) the region rows' diagonal blocks inverted
};

}  // namespace galsculpt
