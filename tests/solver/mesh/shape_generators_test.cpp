#include "solver/mesh/shape_generators.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/mesh/surface_checks.h"
#include "tests/surface_expectations.h"

namespace galsculpt {
namespace {

TEST(ShapeGenerators, IcosphereApproachesTheSphere) {
  const TriMesh m = makeIcosphere(0.1, 3);
  EXPECT_EQ(m.numFaces(), 1280);
  EXPECT_EQ(m.numVertices(), 642);
  test::expectClosedEmbedded(m);
  const double exact = 4.0 / 3.0 * M_PI * 1e-3;
  EXPECT_NEAR(enclosedVolume(m) / exact, 1.0, 0.02);
  for (const Vec3& v : m.vertices) EXPECT_NEAR(v.norm(), 0.1, 1e-12);
}

TEST(ShapeGenerators, CharpyBarHasTheStandardDimensionsAndNotch) {
  const TriMesh m = makeCharpyBar();
  test::expectClosedEmbedded(m);
  const BoundingBox box = boundingBox(m.vertices);
  EXPECT_NEAR(box.size().x(), 0.055, 1e-12);
  EXPECT_NEAR(box.size().y(), 0.010, 1e-12);
  EXPECT_NEAR(box.size().z(), 0.010, 1e-12);
  // Bar volume minus the V-notch prism: depth 2 mm, opening 2*2*tan(22.5 deg).
  const double notch = 0.5 * 0.002 * (2 * 0.002 * std::tan(M_PI / 8)) * 0.010;
  EXPECT_NEAR(enclosedVolume(m), 0.055 * 0.01 * 0.01 - notch, 1e-15);
}

TEST(ShapeGenerators, SteakIsDeterministicLumpyAndClosed) {
  const TriMesh a = makeSteakSlab(0.005);
  const TriMesh b = makeSteakSlab(0.005);
  EXPECT_EQ(a.vertices, b.vertices);
  test::expectClosedEmbedded(a);
  const BoundingBox box = boundingBox(a.vertices);
  EXPECT_GT(box.size().x(), 0.15);
  EXPECT_LT(box.size().y(), 0.05);
  EXPECT_NE(makeSteakSlab(0.005, 7).vertices, a.vertices) << "the seed changes the shape";
  // Near-equilateral faces: the worst aspect (longest edge / shortest altitude) stays small.
  double worst = 0.0;
  for (const Tri& f : a.faces) {
    const Vec3 &p = a.vertices[f[0]], &q = a.vertices[f[1]], &r = a.vertices[f[2]];
    const double longest = std::max({(q - p).norm(), (r - q).norm(), (p - r).norm()});
    const double area2 = (q - p).cross(r - p).norm();
    worst = std::max(worst, longest * longest / area2);
  }
  EXPECT_LT(worst, 8.0);  // 1.15 for an equilateral triangle
}

}  // namespace
}  // namespace galsculpt
