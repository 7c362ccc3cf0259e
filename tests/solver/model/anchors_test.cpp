// An anchor's path (solver/model/anchors.h): offsets linear between keys, held before the first
// and after the last, zero without a path.
#include "solver/model/anchors.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(Anchors, ThePathIsLinearBetweenKeysAndHeldBeyondThem) {
  AnchorConstraint a;
  EXPECT_EQ(anchorOffset(a, 3.0), Vec3::Zero()) << "no path: fixed";
  a.path = {{1.0, Vec3(0, 0, 0)}, {2.0, Vec3(0.2, 0, 0)}, {4.0, Vec3(0.2, -0.4, 0)}};
  EXPECT_EQ(anchorOffset(a, 0.0), Vec3(0, 0, 0));
  EXPECT_EQ(anchorOffset(a, 1.0), Vec3(0, 0, 0));
  EXPECT_TRUE(anchorOffset(a, 1.5).isApprox(Vec3(0.1, 0, 0), 1e-15));
  EXPECT_EQ(anchorOffset(a, 2.0), Vec3(0.2, 0, 0));
  EXPECT_TRUE(anchorOffset(a, 3.0).isApprox(Vec3(0.2, -0.2, 0), 1e-15));
  EXPECT_EQ(anchorOffset(a, 9.0), Vec3(0.2, -0.4, 0));
  a.path = {{0.5, Vec3(1, 2, 3)}};
  EXPECT_EQ(anchorOffset(a, 0.0), Vec3(1, 2, 3)) << "one key: held";
  EXPECT_EQ(anchorOffset(a, 7.0), Vec3(1, 2, 3));
}

}  // namespace
}  // namespace galsculpt
