#include "app/window/camera.h"

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

// A pixel's ray passes through the world points that project onto that pixel, and the projection
// matches the OpenGL matrices the renderer uses.
TEST(OrbitCamera, RaysAndProjectionAgreeWithTheRenderMatrices) {
  OrbitCamera c;
  c.target = Eigen::Vector3d(0.1, -0.2, 0.3);
  c.distance = 2.0;
  c.yaw = 0.7;
  c.pitch = -0.3;
  const int w = 800, h = 600;
  const Eigen::Matrix4d m = (c.projection(double(w) / h) * c.view()).cast<double>();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(0.5, 0.1, -0.2),
                                   Eigen::Vector3d(-0.4, 0.3, 0.6)}) {
    const Eigen::Vector4d clip = m * p.homogeneous();
    const double px = 0.5 * (clip.x() / clip.w() + 1.0) * w;
    const double py = 0.5 * (1.0 - clip.y() / clip.w()) * h;
    const Eigen::Vector3d projected = c.project(p, w, h);
    EXPECT_NEAR(projected.x(), px, 1e-3);
    EXPECT_NEAR(projected.y(), py, 1e-3);
    EXPECT_NEAR(projected.z(), (p - c.eye()).dot(c.forward()), 1e-6);  // float matrices
    Eigen::Vector3d origin, dir;
    c.ray(px, py, w, h, origin, dir);
    EXPECT_NEAR(dir.norm(), 1.0, 1e-12);
    const Eigen::Vector3d toPoint = p - origin;
    EXPECT_NEAR((toPoint - toPoint.dot(dir) * dir).norm(), 0.0, 1e-5) << "the ray misses p";
  }
  Eigen::Vector3d origin, dir;
  c.ray(w / 2.0, h / 2.0, w, h, origin, dir);
  EXPECT_NEAR((dir - c.forward()).norm(), 0.0, 1e-6) << "the centre pixel looks forward";
}

}  // namespace
}  // namespace galsculpt
