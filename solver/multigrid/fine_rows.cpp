#include "solver/multigrid/fine_rows.h"

#include "solver/fem/element_lanes.h"

namespace galsculpt::fine_rows {

#if defined(__x86_64__)
namespace avx2 {
void sweepRow(const Rows& m, int i, const double* b, double* x);
void productRow(const Rows& m, int i, const double* diagonal, const double* x, double* y);
}  // namespace avx2
#endif

namespace {
bool useAvx2() {
#if defined(__x86_64__)
  // laneKernel is null for Avx2 on a CPU without it.
  return kernels::chosenLaneBuild() == kernels::LaneBuild::Avx2 &&
         kernels::laneKernel(kernels::LaneBuild::Avx2) != nullptr;
#else
  return false;
#endif
}
}  // namespace

SweepRow sweepRow() {
#if defined(__x86_64__)
  if (useAvx2()) return &avx2::sweepRow;
#endif
  return nullptr;
}

ProductRow productRow() {
#if defined(__x86_64__)
  if (useAvx2()) return &avx2::productRow;
#endif
  return nullptr;
}

}  // namespace galsculpt::fine_rows
