// The fine smoother's rows (fine_smoother.h) four doubles at a time: a row's 3-vector in the
// lanes of one AVX2 register, each off-diagonal block a column at a time. The CPU's fast path for
// the V-cycle's fine Gauss-Seidel sweeps and residual product, which read the float copy of the
// fine blocks.
//
// Each lane rounds exactly as multigrid_cycle.h's row loops do (the same products and sums in the
// same order, the float entries widened to double, no fused multiply-add), so the choice of build
// changes no bit; a test compares them. The build follows the element lanes' choice
// (element_lanes.h: chosenLaneBuild, GALSCULPT_ELEMENT_LANES): AVX2 where the CPU has it; the
// portable loops otherwise.
#pragma once

namespace galsculpt::fine_rows {

// The smoother's operator in colour order (FineSmoother): row i of the colour order is fine row
// rowOf[i]; its off-diagonal blocks (float, column-major) are blocks + 9 k for k in
// [rowStart[i], rowStart[i + 1]), at columns[k]; inverse + 9 i is its diagonal block's inverse.
struct Rows {
  const int* rowStart;
  const int* columns;
  const float* blocks;
  const double* inverse;
  const int* rowOf;
};

// One Gauss-Seidel update of colour-order row i: x_r = D_r^-1 (b_r - sum_k A_k x_{columns[k]}).
using SweepRow = void (*)(const Rows& rows, int i, const double* b, double* x);
// Row r = rowOf[i] of y = A x: diagonal (9 doubles, column-major) times x_r plus the row's blocks.
using ProductRow = void (*)(const Rows& rows, int i, const double* diagonal, const double* x,
                            double* y);

// The chosen build's kernels; null where it is the portable loops (the caller's own).
SweepRow sweepRow();
ProductRow productRow();

}  // namespace galsculpt::fine_rows
