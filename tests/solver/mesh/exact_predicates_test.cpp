#include "solver/mesh/exact_predicates.h"

#include <gtest/gtest.h>

#include <random>

namespace galsculpt {
namespace {

// Integer coordinates (scaled by a power of two and offset, both exact in doubles) give an
// independent exact reference in 128-bit integers.
__extension__ using I128 = __int128;
int exactSign(const std::array<std::array<std::int64_t, 3>, 4>& p) {
  auto d = [&](int i, int k) { return static_cast<I128>(p[i][k] - p[3][k]); };
  const I128 det = d(0, 0) * (d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1)) +
                   d(0, 1) * (d(1, 2) * d(2, 0) - d(1, 0) * d(2, 2)) +
                   d(0, 2) * (d(1, 0) * d(2, 1) - d(1, 1) * d(2, 0));
  return det > 0 ? 1 : det < 0 ? -1 : 0;
}

TEST(ExactPredicates, SignMatchesTheVolumeOnWellSeparatedPoints) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(orient3d(a, b, c, Vec3(0.2, 0.2, 1.0)),
            tetSixVolume(Vec3(0.2, 0.2, 1.0), a, b, c) > 0 ? 1 : -1);
  EXPECT_EQ(orient3d(a, b, c, Vec3(0.2, 0.2, -1.0)), -orient3d(a, b, c, Vec3(0.2, 0.2, 1.0)));
  EXPECT_EQ(orient3d(a, b, c, Vec3(5.0, -3.0, 0.0)), 0);
}

// Points on a plane with large integer coefficients, then nudged by -1, 0 or +1 unit: the
// plain floating-point determinant is wrong on many of them; the predicate never is.
TEST(ExactPredicates, NearlyCoplanarPointsAreDecidedExactly) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> coord(-(1LL << 29), 1LL << 29);
  const double unit = 0x1.0p-24, offset = 4096.0;
  int naiveWrong = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::array<std::array<std::int64_t, 3>, 4> p;
    for (auto& q : p) {
      q[0] = coord(rng);
      q[1] = coord(rng);
      q[2] = 3 * q[0] - 5 * q[1] + 12345;  // the plane z = 3x - 5y + 12345
    }
    p[3][2] += static_cast<int>(trial % 3) - 1;
    std::array<Vec3, 4> v;
    for (int i = 0; i < 4; ++i) {
      for (int k = 0; k < 3; ++k) v[i][k] = offset + unit * static_cast<double>(p[i][k]);
    }
    const int expected = exactSign(p);
    ASSERT_EQ(orient3d(v[0], v[1], v[2], v[3]), expected) << "trial " << trial;
    ASSERT_EQ(orient3dExact(v[0], v[1], v[2], v[3]), expected) << "trial " << trial;
    const Vec3 ad = v[0] - v[3], bd = v[1] - v[3], cd = v[2] - v[3];
    const double naive = ad.dot(bd.cross(cd));
    naiveWrong += (naive > 0 ? 1 : naive < 0 ? -1 : 0) != expected;
  }
  EXPECT_GT(naiveWrong, 100) << "the cases must be hard for plain floating point";
}

}  // namespace
}  // namespace galsculpt
