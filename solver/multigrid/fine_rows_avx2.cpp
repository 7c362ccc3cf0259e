// fine_rows.h's AVX2 kernels (compiled with -mavx2, without FMA or contraction: each lane rounds
// as the portable loops do). Masked loads and stores touch a row's three entries only: the
// fourth lane carries nothing, and the entry after a row may be another thread's.
#include "solver/multigrid/fine_rows.h"

#if defined(__x86_64__)  // (fine_rows.cpp offers these kernels on x86-64 only)
#include <immintrin.h>

namespace galsculpt::fine_rows::avx2 {
namespace {

inline __m256i threeLanes() {
  return _mm256_setr_epi64x(-1, -1, -1, 0);
}
inline __m128i threeFloats() {
  return _mm_setr_epi32(-1, -1, -1, 0);
}

// t = a[.]x0 + a[. + 3]x1 + a[. + 6]x2 in each lane, as ((a0 x0 + a3 x1) + a6 x2): the order of
// the portable loops' sums.
inline __m256d blockTimes(const float* a, const double* x) {
  const __m256d c0 = _mm256_cvtps_pd(_mm_maskload_ps(a, threeFloats()));
  const __m256d c1 = _mm256_cvtps_pd(_mm_maskload_ps(a + 3, threeFloats()));
  const __m256d c2 = _mm256_cvtps_pd(_mm_maskload_ps(a + 6, threeFloats()));
  const __m256d sum = _mm256_add_pd(_mm256_mul_pd(c0, _mm256_broadcast_sd(x)),
                                    _mm256_mul_pd(c1, _mm256_broadcast_sd(x + 1)));
  return _mm256_add_pd(sum, _mm256_mul_pd(c2, _mm256_broadcast_sd(x + 2)));
}

inline __m256d blockTimes(const double* a, __m256d v) {
  const __m256d c0 = _mm256_maskload_pd(a, threeLanes());
  const __m256d c1 = _mm256_maskload_pd(a + 3, threeLanes());
  const __m256d c2 = _mm256_maskload_pd(a + 6, threeLanes());
  const __m256d v0 = _mm256_permute4x64_pd(v, 0x00);
  const __m256d v1 = _mm256_permute4x64_pd(v, 0x55);
  const __m256d v2 = _mm256_permute4x64_pd(v, 0xaa);
  const __m256d sum = _mm256_add_pd(_mm256_mul_pd(c0, v0), _mm256_mul_pd(c1, v1));
  return _mm256_add_pd(sum, _mm256_mul_pd(c2, v2));
}

}  // namespace

void sweepRow(const Rows& m, int i, const double* b, double* x) {
  const int r = m.rowOf[i];
  __m256d rhs = _mm256_maskload_pd(b + 3 * r, threeLanes());
  const int end = m.rowStart[i + 1];
  for (int k = m.rowStart[i]; k < end; ++k)
    rhs = _mm256_sub_pd(rhs, blockTimes(m.blocks + 9 * static_cast<long>(k), x + 3 * m.columns[k]));
  _mm256_maskstore_pd(x + 3 * r, threeLanes(),
                      blockTimes(m.inverse + 9 * static_cast<long>(i), rhs));
}

void productRow(const Rows& m, int i, const double* diagonal, const double* x, double* y) {
  const int r = m.rowOf[i];
  const __m256d sign = _mm256_set1_pd(-0.0);
  __m256d acc =
      _mm256_xor_pd(blockTimes(diagonal, _mm256_maskload_pd(x + 3 * r, threeLanes())), sign);
  const int end = m.rowStart[i + 1];
  for (int k = m.rowStart[i]; k < end; ++k)
    acc = _mm256_sub_pd(acc, blockTimes(m.blocks + 9 * static_cast<long>(k), x + 3 * m.columns[k]));
  _mm256_maskstore_pd(y + 3 * r, threeLanes(), _mm256_xor_pd(acc, sign));
}

}  // namespace galsculpt::fine_rows::avx2

#endif
