#include "solver/fem/colliders.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(Colliders, PlaneSphereAndBoxDistances) {
  Collider plane;
  plane.point = Vec3(0, -1, 0);
  EXPECT_NEAR(colliderDistance(plane, Vec3(3, -1.5, 2), 0).distance, -0.5, 1e-15);
  Collider sphere;
  sphere.type = Collider::Type::Sphere;
  sphere.center = Vec3(1, 0, 0);
  sphere.radius = 0.5;
  const ContactSample s = colliderDistance(sphere, Vec3(1, 0.25, 0), 0);
  EXPECT_NEAR(s.distance, -0.25, 1e-15);
  EXPECT_TRUE(s.normal.isApprox(Vec3::UnitY()));
  Collider box;
  box.type = Collider::Type::Box;
  box.halfExtents = Vec3(1, 2, 3);
  EXPECT_NEAR(colliderDistance(box, Vec3(0.9, 0, 0), 0).distance, -0.1, 1e-12);
  EXPECT_TRUE(colliderDistance(box, Vec3(0.9, 0, 0), 0).normal.isApprox(Vec3::UnitX()));
  EXPECT_NEAR(colliderDistance(box, Vec3(4, 5, 3), 0).distance, std::hypot(3.0, 3.0), 1e-12);
}

TEST(Colliders, LinearAndPendulumMotion) {
  Collider moving;
  moving.type = Collider::Type::Sphere;
  moving.radius = 1;
  moving.motion.type = ColliderMotion::Type::Linear;
  moving.motion.velocity = Vec3(2, 0, 0);
  EXPECT_NEAR(colliderDistance(moving, Vec3(4, 0, 0), 1.0).distance, 1.0, 1e-12);

  // A hammer hanging 1 m below its pivot, swinging about x at 2 rad/s: after pi/4 s it has
  // turned 90 degrees, from straight down to pointing along +y... no: along -z... check by pose.
  Collider hammer;
  hammer.type = Collider::Type::Sphere;
  hammer.radius = 0.1;
  hammer.center = Vec3(0, 0, -1);
  hammer.motion.type = ColliderMotion::Type::Pendulum;
  hammer.motion.pivot = Vec3::Zero();
  hammer.motion.axis = Vec3::UnitX();
  hammer.motion.angularVelocity = 2.0;
  const double t = M_PI / 4;
  const Vec3 centre = colliderRotation(hammer, t) * hammer.center + colliderTranslation(hammer, t);
  EXPECT_NEAR((centre - Vec3(0, 1, 0)).norm(), 0.0, 1e-12)
      << "omega x r at the bottom points along +y";
  EXPECT_NEAR(colliderDistance(hammer, Vec3(0, 1, 0), t).distance, -0.1, 1e-12);
}

}  // namespace
}  // namespace galsculpt
