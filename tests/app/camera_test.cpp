#include "app/camera.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(OrbitCamera, TargetProjectsToTheCentre) {
  OrbitCamera c;
  c.target = Eigen::Vector3d(1, 2, 3);
  c.distance = 5;
  const Eigen::Vector4f p = c.projection(1.5) * c.view() * Eigen::Vector4f(1, 2, 3, 1);
  EXPECT_NEAR(p.x() / p.w(), 0.0, 1e-5);
  EXPECT_NEAR(p.y() / p.w(), 0.0, 1e-5);
  EXPECT_GT(p.z() / p.w(), -1.0);
  EXPECT_LT(p.z() / p.w(), 1.0);
}

TEST(OrbitCamera, FrameKeepsTheWholeBoxInView) {
  OrbitCamera c;
  BoundingBox box;
  box.min = Eigen::Vector3d(-1, -2, -0.5);
  box.max = Eigen::Vector3d(3, 1, 0.5);
  c.frame(box);
  const Eigen::Matrix4f m = c.projection(1.0) * c.view();
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1) ? box.max.x() : box.min.x(),
                                 (i & 2) ? box.max.y() : box.min.y(),
                                 (i & 4) ? box.max.z() : box.min.z());
    const Eigen::Vector4f p = m * Eigen::Vector4f(corner.x(), corner.y(), corner.z(), 1.0f);
    EXPECT_LE(std::abs(p.x() / p.w()), 1.0f);
    EXPECT_LE(std::abs(p.y() / p.w()), 1.0f);
  }
}

TEST(OrbitCamera, TopViewIsStillAValidMatrix) {
  OrbitCamera c;
  c.viewTop();
  EXPECT_TRUE(c.view().allFinite());
  c.orbit(0, 10);  // clamped short of the pole
  EXPECT_LT(c.pitch, 1.56);
  EXPECT_TRUE(c.view().allFinite());
}

}  // namespace
}  // namespace galsculpt
