#include "engine/session/tool_reach.h"

#include <gtest/gtest.h>

#include <random>

namespace galsculpt {
namespace {

// Against a brute-force minimum over a fine grid of the triangle's points.
TEST(ToolReach, DistanceToATriangleIsTheNearestOfItsPoints) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.2, 0.8, 0.1);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  for (int k = 0; k < 40; ++k) {
    const Vec3 p(u(rng), u(rng), u(rng));
    double brute = 1e9;
    const int n = 200;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Vec3 q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
        brute = std::min(brute, (p - q).norm());
      }
    EXPECT_NEAR(distanceToTriangle(p, a, b, c), brute, 5e-3) << p.transpose();
    EXPECT_LE(distanceToTriangle(p, a, b, c), brute + 1e-12);
  }
  // On the triangle: zero; a degenerate triangle: its nearest corner or edge.
  EXPECT_NEAR(distanceToTriangle(Vec3(0.3, 0.2, 0.025), a, b, c), 0.0, 1e-12);
  EXPECT_NEAR(distanceToTriangle(Vec3(0.5, 1, 0), a, b, Vec3(2, 0, 0)), 1.0, 1e-12);
}

TEST(ToolReach, ABladeIsAsFarAsItsNearestTriangleFromTheNearestPoint) {
  const std::vector<BladeTriangle> blade =
      sweptBladeSurface(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(-1, -1, 0), Vec3(1, -1, 0));
  EXPECT_NEAR(distanceToBlade(blade, {Vec3(0, -0.5, 0.3), Vec3(0, -0.5, -0.2)}), 0.2, 1e-12);
  EXPECT_NEAR(distanceToBlade(blade, {Vec3(0, 1, 0)}), 1.0, 1e-12);
}

}  // namespace
}  // namespace galsculpt
